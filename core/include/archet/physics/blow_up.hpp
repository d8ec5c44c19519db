#pragma once
// A simulation that went non-finite (NaN or infinity) must never be heard or written as
// sound: libsndfile turns NaN into full-scale DC. Renders check every output sample and, once
// per block, the whole state; the first non-finite value stops them with a message naming the
// time and the element that blew up.

#include <optional>
#include <string>

#include "archet/physics/simulation.hpp"

namespace archet {

/// The first mass whose position is not finite, as "mass \"s5\" (position nan)", or nothing.
std::optional<std::string> find_blown_up_element(const Simulation& sim);

/// True when the output, every probe and every position are finite.
bool simulation_is_finite(const Simulation& sim);

/// Throws InputError: the simulation stopped being finite at its current time, naming the
/// element (or the output when the state is finite but the output overflowed).
[[noreturn]] void throw_blow_up(const Simulation& sim);

}  // namespace archet
