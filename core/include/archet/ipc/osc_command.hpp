#pragma once
// Archet's OSC address space, decoded. A message arrives from any program on the network
// (Max, Pd, SuperCollider, TouchOSC, oscsend): its address must be one of ours, its arguments
// of the right count and type, its numbers finite and in range. What this accepts is safe to
// act on; what it refuses comes back as a sentence naming the address and what to send.
//
//   /archet/bow/slide  f      the hand on the bow's sliding axis, m
//   /archet/bow/press  f      the hand on the bow's pressure axis, m (below 0: lifted)
//   /archet/finger     f      the model's finger: its position, 0…1 (the sounding share)
//   /archet/finger/pressure f the model's finger: its pressure, 0…1
//   /archet/param      s f    any parameter, "ELEMENT.PARAM" and its value
//   /archet/record     s      "start" or "stop" a take
//
// A number may be sent as float, double, int32 or int64. (The OSC wire format itself is
// parsed by liblo; this sees its path and its typed arguments.)

#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "archet/model/parameter_name.hpp"

namespace archet::ipc {

/// One argument of an OSC message: `type` is its OSC type tag ('f', 'd', 'i', 'h', 's', …);
/// numbers are in `number`, strings in `text`.
struct OscArgument {
    char type = 'f';
    double number = 0;
    std::string text;
};

struct OscCommand {
    enum class Kind { Slide, Press, Finger, FingerPressure, Parameter, RecordStart, RecordStop };
    Kind kind = Kind::Slide;
    double value = 0;         ///< m, 0…1 or the parameter's value
    ParameterName parameter;  ///< Parameter only
};

/// The addresses above, with their argument types, for messages and docs.
std::string_view osc_address_space();

/// The command, or why the message was refused.
std::variant<OscCommand, std::string> decode_osc(std::string_view path,
                                                 std::span<const OscArgument> arguments);

}  // namespace archet::ipc
