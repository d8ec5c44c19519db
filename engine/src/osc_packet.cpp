#include "archet/engine/osc_packet.hpp"

#include <lo/lo.h>

#include <cstring>
#include <memory>
#include <vector>

namespace archet {

std::variant<ipc::OscCommand, std::string> decode_osc_packet(const std::uint8_t* data,
                                                             std::size_t size) {
    if (size == 0 || size > kMaxOscPacket)
        return "an OSC packet of " + std::to_string(size) + " bytes; send one message of at most " +
               std::to_string(kMaxOscPacket);
    if (size >= 8 && std::memcmp(data, "#bundle", 8) == 0)
        return std::string("an OSC bundle; send its messages one by one");
    std::vector<std::uint8_t> copy(data, data + size);  // liblo takes a mutable buffer
    int result = 0;
    const std::unique_ptr<void, void (*)(lo_message)> message(
        lo_message_deserialise(copy.data(), copy.size(), &result), lo_message_free);
    if (!message) return "a malformed OSC message (liblo error " + std::to_string(result) + ")";
    const char* path = lo_get_path(copy.data(), static_cast<ssize_t>(copy.size()));
    const char* types = lo_message_get_types(message.get());
    lo_arg** argv = lo_message_get_argv(message.get());
    const int argc = lo_message_get_argc(message.get());
    if (!path || !types) return std::string("a malformed OSC message");
    std::vector<ipc::OscArgument> arguments;
    for (int i = 0; i < argc; ++i) {
        ipc::OscArgument a;
        a.type = types[i];
        switch (types[i]) {
            case LO_FLOAT:
                a.number = argv[i]->f;
                break;
            case LO_DOUBLE:
                a.number = argv[i]->d;
                break;
            case LO_INT32:
                a.number = argv[i]->i;
                break;
            case LO_INT64:
                a.number = static_cast<double>(argv[i]->h);
                break;
            case LO_STRING:
            case LO_SYMBOL:
                a.type = 's';
                a.text = &argv[i]->s;
                break;
            default:
                break;  // kept with its tag: decode_osc names it in its refusal
        }
        arguments.push_back(std::move(a));
    }
    return ipc::decode_osc(path, arguments);
}

}  // namespace archet
