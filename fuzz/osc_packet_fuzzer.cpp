// OSC packets as any program on the network could send them to `archet engine --osc`: liblo
// parses or refuses them, the decoder accepts or refuses, and what it accepts is in range.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <variant>

#include "archet/engine/osc_packet.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using Kind = archet::ipc::OscCommand::Kind;
    const auto decoded = archet::decode_osc_packet(data, size);
    if (const auto* c = std::get_if<archet::ipc::OscCommand>(&decoded)) {
        if (!std::isfinite(c->value)) __builtin_trap();
        if ((c->kind == Kind::Finger || c->kind == Kind::FingerPressure) &&
            (c->value < 0 || c->value > 1))
            __builtin_trap();
        if (c->kind == Kind::Parameter &&
            (c->parameter.element.empty() || c->parameter.parameter.empty()))
            __builtin_trap();
    } else if (std::get<std::string>(decoded).empty()) {
        __builtin_trap();  // a refusal always says why
    }
    return 0;
}
