#pragma once
// Decodes a command frame read from the shared segment. Everything in it came from another
// process and may be garbage: the opcode must be known, the text terminated, the numbers
// finite and in range. The engine acts only on what this accepts.

#include <string>
#include <variant>

#include "archet/ipc/segment_layout.hpp"
#include "archet/model/parameter_name.hpp"

namespace archet::ipc {

struct DecodedCommand {
    Opcode opcode = Opcode::Play;
    std::uint32_t sequence = 0;
    std::string text;         ///< a model path, a take folder, or ELEMENT.PARAM as sent
    ParameterName parameter;  ///< SetParameter: the parameter it sets
    double value = 0, slide = 0, press = 0;
};

/// The command, or why it was refused (for the Error status frame).
std::variant<DecodedCommand, std::string> decode_command(const CommandFrame& frame);

}  // namespace archet::ipc
