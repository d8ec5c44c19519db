#include "archet/engine/osc_packet.hpp"

#include <lo/lo.h>

#include <cstring>
#include <memory>
#include <vector>

namespace archet {

namespace {

template <class T>
T read_as(const char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof value);
    return value;
}

}  // namespace

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
    // liblo's arguments lie in its buffer at 4-byte alignment: read their bytes, not the union
    // (whose 8-byte members would be read misaligned).
    for (int i = 0; i < argc; ++i) {
        const auto* bytes = reinterpret_cast<const char*>(argv[i]);
        ipc::OscArgument a;
        a.type = types[i];
        switch (types[i]) {
            case LO_FLOAT:
                a.number = read_as<float>(bytes);
                break;
            case LO_DOUBLE:
                a.number = read_as<double>(bytes);
                break;
            case LO_INT32:
                a.number = read_as<std::int32_t>(bytes);
                break;
            case LO_INT64:
                a.number = static_cast<double>(read_as<std::int64_t>(bytes));
                break;
            case LO_STRING:
            case LO_SYMBOL:
                a.type = 's';
                a.text = bytes;  // liblo checked its terminator
                break;
            default:
                break;  // kept with its tag: decode_osc names it in its refusal
        }
        arguments.push_back(std::move(a));
    }
    return ipc::decode_osc(path, arguments);
}

}  // namespace archet
