#pragma once
// The string every contender of the peer benchmark plays: Archet's 60-mass bowed string at
// 220 Hz (`archet new bowed-string --pitch 220 --masses 60`), bowed at 0.1 m/s.

#include "archet/builders/bowed_string.hpp"

namespace archet::peers {

constexpr double kPitch = 220.0;
constexpr int kMasses = 60;
constexpr double kBowSpeed = 0.1;  ///< m/s
constexpr double kBowForce = 0.5;  ///< N, for mi.lib's friction curve
constexpr double kBowMuS = 0.8, kBowV0 = 0.1;

/// The shipped string, with its violin body or (`bare`) the string and bridges alone, the
/// same elements as the mi.lib model.
inline BowedStringOptions string_options(bool with_body) {
    BowedStringOptions o;
    o.pitch = kPitch;
    o.masses = kMasses;
    if (!with_body) o.body = "none";
    return o;
}

}  // namespace archet::peers
