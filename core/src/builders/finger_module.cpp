// The left hand's finger on a built string: a stiff, damped stop along the whole string, from
// the bridge to the nut, so that its position is the sounding length's share of the string.

#include <algorithm>
#include <cmath>

#include "archet/builders/bowed_string.hpp"

namespace archet {

void add_finger(Model& model, const BowedStringOptions& o, int masses) {
    Lia finger;
    finger.id = "finger", finger.kind = LiaKind::Finger, finger.rate = "audio";
    finger.along.push_back("bridge");
    double stiffness = 0;
    int links = 0;
    for (int i = 1; i <= masses; ++i) {
        finger.along.push_back("s" + std::to_string(i));
        if (const Lia* link = model.find_lia("k" + std::to_string(i)))
            stiffness += link->stiffness, ++links;
    }
    finger.along.push_back("nut");
    // Pressed, a hundred times the string's links and two hundred times its wave impedance:
    // waves reflect from it as from a fingerboard (under 10⁻⁴ of their energy lost). A light
    // touch, pressure 0.01, damps the string there with twice its impedance, a match that
    // leaves only the modes with a node at the finger: the harmonics.
    const double impedance = std::sqrt(o.tension * o.linear_density);
    finger.stiffness = 100.0 * stiffness / std::max(links, 1);
    finger.damping = 200.0 * impedance;
    finger.finger_position = o.finger_position;
    finger.pressure = 1.0;
    finger.display = {{40.0 * (masses + 1) * o.finger_position, 60.0}};
    model.lias.push_back(finger);
}

}  // namespace archet
