// What a running simulation reads out: the force for the device, the probes and the output
// (the energy books are in energy.cpp).

#include <algorithm>
#include <cmath>

#include "archet/physics/simulation.hpp"

namespace archet {

GestureSample Simulation::device_force() const {
    GestureSample f{};
    for (const auto& lv : model_.levels)
        for (const auto& g : lv.gestures)
            (g.axis == GestureAxis::Slide ? f.slide : f.press) += g.force_scale * g.force;
    return f;
}

double Simulation::power_in() const {
    double p = 0;
    for (const auto& lv : model_.levels)
        for (const auto& g : lv.gestures) p += g.power;
    return p;
}

double Simulation::probe(std::size_t i) const {
    const CompiledProbe& p = model_.probes[i];
    switch (p.kind) {
        case ProbeKind::Position:
            return position(p.mat);
        case ProbeKind::Velocity:
            return velocity(p.mat);
        case ProbeKind::Force:
            return model_.levels[p.mat.level].watched_force[p.watched];
        case ProbeKind::NormalForce:
            return model_.bows[p.bow].normal;
        case ProbeKind::FrictionForce:
            return model_.bows[p.bow].friction;
        case ProbeKind::SlipVelocity:
            return model_.bows[p.bow].slip_velocity;
        case ProbeKind::Energy:
            return stored_energy();
        case ProbeKind::PowerIn:
            return power_in();
    }
    return 0;
}

}  // namespace archet
