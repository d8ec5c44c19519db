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

/// The strings the contenders play.
enum class PeerString {
    Paper,  ///< the paper's chaplet: link damping alone, bridges, a point bow (`--paper`)
    Bare,   ///< the shipped string without its body: losses to its rest points, bridges, and
            ///< a bow spread over three masses
    Body,   ///< the shipped string with its violin body
};

inline BowedStringOptions string_options(PeerString string) {
    BowedStringOptions o;
    o.pitch = kPitch;
    o.masses = kMasses;
    o.paper = string == PeerString::Paper;
    if (string == PeerString::Bare) o.body = "none";
    return o;
}

}  // namespace archet::peers
