#include "archet/ipc/command_decoder.hpp"

#include <cmath>
#include <cstring>

namespace archet::ipc {

namespace {
constexpr double kMaxGesture = 100;  // m: far beyond any device, short of overflow
}

std::variant<DecodedCommand, std::string> decode_command(const CommandFrame& f) {
    if (std::memchr(f.text, '\0', kTextSize) == nullptr)
        return "command text is not NUL-terminated";
    DecodedCommand c;
    c.sequence = f.sequence;
    c.text = f.text;
    c.value = f.value, c.slide = f.slide, c.press = f.press;
    switch (static_cast<Opcode>(f.opcode)) {
        case Opcode::LoadModel:
        case Opcode::StartTake:
            if (c.text.empty()) return std::string(opcode_name(f.opcode)) + " needs a path";
            break;
        case Opcode::SetParameter:
            try {
                c.parameter = ParameterName::parse(c.text);
            } catch (const std::exception& e) {
                return std::string(e.what());
            }
            if (!std::isfinite(c.value)) return c.text + ": the value must be a finite number";
            break;
        case Opcode::Gesture:
            if (!std::isfinite(c.slide) || !std::isfinite(c.press) ||
                std::abs(c.slide) > kMaxGesture || std::abs(c.press) > kMaxGesture)
                return std::string("gesture positions must be finite and within ±100 m");
            break;
        case Opcode::Play:
        case Opcode::Stop:
        case Opcode::Quit:
        case Opcode::StopTake:
            break;
        default:
            return "unknown opcode " + std::to_string(f.opcode);
    }
    c.opcode = static_cast<Opcode>(f.opcode);
    return c;
}

}  // namespace archet::ipc
