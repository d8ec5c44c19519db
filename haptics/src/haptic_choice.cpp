#include "archet/haptic_choice.hpp"

#include "archet/common/input_error.hpp"
#include "archet/evdev_device.hpp"
#include "archet/sdl_device.hpp"

namespace archet {

HapticChoice open_haptic_device(const std::string& name) {
    HapticChoice choice;
    if (name == "none") return choice;
    if (name == "sim") {
        auto hand = std::make_unique<SimulatedHand>();
        choice.hand = hand.get();
        choice.device = std::move(hand);
        return choice;
    }
    if (name.rfind("evdev:", 0) == 0 && name.size() > 6) {
        choice.device = std::make_unique<EvdevDevice>(name.substr(6));
        return choice;
    }
    if (name.rfind("sdl:", 0) == 0 && name.size() > 4) {
        const std::string index = name.substr(4);
        if (index.find_first_not_of("0123456789") != std::string::npos || index.size() > 6)
            throw InputError("--haptic", "\"" + name +
                                             "\": the SDL joystick is a number, as "
                                             "`archet devices` lists them (sdl:0, sdl:1, ...)");
        auto joystick = std::make_unique<SdlDevice>(std::stoi(index));
        if (!joystick->force_feedback())
            choice.note = "\"" + joystick->capabilities().name +
                          "\" has no force feedback: playing with its positions only";
        choice.device = std::move(joystick);
        return choice;
    }
    throw InputError("--haptic", "\"" + name +
                                     "\" is not a haptic device; use none, sim, "
                                     "evdev:/dev/input/eventN or sdl:INDEX");
}

std::vector<HapticDeviceInfo> list_haptic_choices() {
    std::vector<HapticDeviceInfo> choices = list_evdev_devices();
    for (HapticDeviceInfo& joystick : list_sdl_joysticks()) choices.push_back(std::move(joystick));
    choices.push_back({"sim", "", "simulated hand", 2, true});
    return choices;
}

std::string describe(const HapticDeviceInfo& d) {
    if (d.backend == "sim") return "sim: simulated hand (always available)";
    return d.backend + " " + d.address + ": " + d.name +
           (d.force_feedback ? " (force feedback)" : " (positions only)");
}

}  // namespace archet
