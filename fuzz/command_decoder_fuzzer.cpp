// The engine's command decoder on arbitrary frames, as another process could write them into
// the shared segment: it accepts or refuses, and what it accepts is sane.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <variant>

#include "archet/ipc/command_decoder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    archet::ipc::CommandFrame frame;
    std::memset(&frame, 0xA5, sizeof frame);  // what is not given stays garbage
    std::memcpy(&frame, data, std::min(size, sizeof frame));
    const auto decoded = archet::ipc::decode_command(frame);
    if (const auto* c = std::get_if<archet::ipc::DecodedCommand>(&decoded)) {
        if (c->text.size() >= archet::ipc::kTextSize) __builtin_trap();
        if (c->opcode == archet::ipc::Opcode::Gesture &&
            (!std::isfinite(c->slide) || std::abs(c->press) > 100))
            __builtin_trap();
    }
    return 0;
}
