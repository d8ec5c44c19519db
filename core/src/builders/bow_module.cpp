// The bow module of the paper: two bow masses held by the hand's two gesture points, and the
// quadripolar friction module between the bow and the string.

#include "archet/builders/bowed_string.hpp"

namespace archet {

void add_bow_module(Model& model, const BowedStringOptions& o, const std::string& string_mass) {
    auto mat = [](const std::string& id, MatKind kind, const std::string& rate, double mass) {
        Mat m;
        m.id = id, m.kind = kind, m.rate = rate, m.mass = mass;
        return m;
    };
    Mat hand_slide = mat("hand_slide", MatKind::Gesture, "haptic", 0);
    hand_slide.axis = GestureAxis::Slide;
    Mat hand_press = mat("hand_press", MatKind::Gesture, "haptic", 0);
    hand_press.axis = GestureAxis::Press;
    model.mats.push_back(mat("bow", MatKind::Mass, "audio", o.bow_mass));
    model.mats.push_back(mat("bow_press", MatKind::Mass, "audio", o.press_mass));
    model.mats.push_back(mat("surface", MatKind::Fixed, "audio", 0));
    model.mats.push_back(hand_slide);
    model.mats.push_back(hand_press);

    // The hand's points tick at the haptic rate; the springs that hold the bow run at the
    // bow's rate and see the hand's steps, so the coupling is exactly passive at every step
    // (a spring at the haptic rate would hold its force, which is passive only on average).
    auto hold = [](const std::string& id, const std::string& from, const std::string& to, double k,
                   double z) {
        Lia l;
        l.id = id, l.kind = LiaKind::SpringDamper, l.rate = "audio";
        l.from = from, l.to = to, l.stiffness = k, l.damping = z;
        return l;
    };
    model.lias.push_back(hold("bow_hold", "hand_slide", "bow", o.bow_stiffness, o.bow_damping));
    model.lias.push_back(
        hold("press_hold", "hand_press", "bow_press", o.press_stiffness, o.press_damping));
    Lia friction;
    friction.id = "friction", friction.kind = LiaKind::BowFriction, friction.rate = "audio";
    friction.from = "bow", friction.to = string_mass, friction.press = "bow_press",
    friction.surface = "surface";
    friction.stiffness = o.buffer_stiffness, friction.damping = o.buffer_damping;
    friction.mu_static = o.mu_s, friction.mu_dynamic = o.mu_d, friction.v0 = o.v0;
    model.lias.push_back(friction);
}

}  // namespace archet
