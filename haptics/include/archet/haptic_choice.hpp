#pragma once
// Opens the haptic device a command line names: "none", "sim" (a simulated hand),
// "evdev:PATH" (a force-feedback joystick) or "sdl:INDEX" (a joystick through SDL2).

#include <memory>
#include <string>

#include "archet/haptic_device.hpp"
#include "archet/simulated_hand.hpp"

namespace archet {

struct HapticChoice {
    std::unique_ptr<HapticDevice> device;  ///< null for "none"
    SimulatedHand* hand = nullptr;         ///< the device, when it is the simulated hand
    std::string note;  ///< what the player should know, e.g. that it renders no force
};

/// Throws InputError for an unknown name or a device that cannot be used.
HapticChoice open_haptic_device(const std::string& name);

}  // namespace archet
