#pragma once
// Opens the haptic device a command line names: "none", "sim" (a simulated hand),
// "evdev:PATH" (a force-feedback joystick) or "sdl:INDEX" (a joystick through SDL2), and
// lists the devices found now under those names: `archet devices` and the studio's settings
// both read this one list.

#include <memory>
#include <string>
#include <vector>

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

/// The joysticks found now (evdev, then SDL) and the simulated hand, always last. Each id
/// opens with open_haptic_device; "none" (no device) is not listed.
std::vector<HapticDeviceInfo> list_haptic_choices();

/// Its line in `archet devices`: "evdev PATH: NAME (force feedback)", "sdl N: NAME
/// (positions only)", "sim: simulated hand (always available)".
std::string describe(const HapticDeviceInfo& device);

}  // namespace archet
