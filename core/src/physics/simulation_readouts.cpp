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

bool Simulation::read_probe_row(ProbeRows probes, std::size_t tick) const {
    const std::size_t count = model_.probes.size();
    double* const row = probes.values + tick * count;
    bool finite = true;
    for (std::size_t p = 0; p < count; ++p)
        if (probes.energy || model_.probes[p].kind != ProbeKind::Energy) {
            row[p] = probe(p);
            finite = finite && std::isfinite(row[p]);
        }
    return finite;
}

}  // namespace archet
