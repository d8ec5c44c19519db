#include "archet/haptic_choice.hpp"

#include "archet/evdev_device.hpp"
#include "archet/input_error.hpp"

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
    throw InputError(
        "--haptic",
        "\"" + name + "\" is not a haptic device; use none, sim or evdev:/dev/input/eventN");
}

}  // namespace archet
