#pragma once
// One UDP datagram from the network, decoded into an Archet command: liblo parses the OSC
// wire format (and refuses what is malformed), decode_osc() checks the address and arguments.
// Bundles are refused: Archet acts on each message as it arrives.

#include <cstddef>
#include <cstdint>
#include <string>
#include <variant>

#include "archet/ipc/osc_command.hpp"

namespace archet {

/// The largest datagram read (bytes); a longer one is cut and refused as malformed.
inline constexpr std::size_t kMaxOscPacket = 8192;

std::variant<ipc::OscCommand, std::string> decode_osc_packet(const std::uint8_t* data,
                                                             std::size_t size);

}  // namespace archet
