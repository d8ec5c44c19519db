#include "archet/model/model.hpp"

#include <algorithm>
#include <utility>

namespace archet {

namespace {
template <class Vec>
auto find_by_id(Vec& items, const std::string& id) -> decltype(&items[0]) {
    auto it = std::find_if(items.begin(), items.end(), [&](const auto& e) { return e.id == id; });
    return it == items.end() ? nullptr : &*it;
}
}  // namespace

const Mat* Model::find_mat(const std::string& id) const {
    return find_by_id(mats, id);
}
const Lia* Model::find_lia(const std::string& id) const {
    return find_by_id(lias, id);
}
const RateLevel* Model::find_rate(const std::string& id) const {
    return find_by_id(rates, id);
}
Mat* Model::find_mat(const std::string& id) {
    return find_by_id(mats, id);
}
Lia* Model::find_lia(const std::string& id) {
    return find_by_id(lias, id);
}

const char* to_string(MatKind k) {
    switch (k) {
        case MatKind::Mass:
            return "mass";
        case MatKind::Fixed:
            return "fixed";
        case MatKind::Oscillator:
            return "oscillator";
        case MatKind::Gesture:
            return "gesture";
        case MatKind::ModalPoint:
            return "modal_point";
    }
    return "?";
}

const Lia* first_finger(const Model& model) {
    for (const auto& l : model.lias)
        if (l.kind == LiaKind::Finger) return &l;
    return nullptr;
}

const Lia* first_bow(const Model& model) {
    for (const auto& l : model.lias)
        if (l.kind == LiaKind::BowFriction) return &l;
    return nullptr;
}

Lia* first_bow(Model& model) {
    return const_cast<Lia*>(first_bow(std::as_const(model)));
}

const char* to_string(LiaKind k) {
    switch (k) {
        case LiaKind::Spring:
            return "spring";
        case LiaKind::Damper:
            return "damper";
        case LiaKind::SpringDamper:
            return "spring_damper";
        case LiaKind::Buffer:
            return "buffer";
        case LiaKind::BowFriction:
            return "bow_friction";
        case LiaKind::Finger:
            return "finger";
    }
    return "?";
}

const char* to_string(GestureAxis a) {
    return a == GestureAxis::Slide ? "slide" : "press";
}

const char* to_string(ProbeKind k) {
    switch (k) {
        case ProbeKind::Position:
            return "position";
        case ProbeKind::Velocity:
            return "velocity";
        case ProbeKind::Force:
            return "force";
        case ProbeKind::NormalForce:
            return "normal_force";
        case ProbeKind::FrictionForce:
            return "friction_force";
        case ProbeKind::SlipVelocity:
            return "slip_velocity";
        case ProbeKind::Energy:
            return "energy";
        case ProbeKind::PowerIn:
            return "power_in";
    }
    return "?";
}

const char* to_string(Output::Signal s) {
    switch (s) {
        case Output::Signal::Position:
            return "position";
        case Output::Signal::Velocity:
            return "velocity";
        case Output::Signal::Force:
            return "force";
    }
    return "?";
}

const char* to_string(Control::Source s) {
    switch (s) {
        case Control::Source::Envelope:
            return "envelope";
        case Control::Source::Gesture:
            return "gesture";
        case Control::Source::Position:
            return "position";
    }
    return "?";
}

}  // namespace archet
