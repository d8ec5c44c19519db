// What a running simulation reads out: the force for the device, the probes and the output
// (the energy books are in energy.cpp).

#include <algorithm>
#include <cmath>

#include "archet/physics/modal_point_position.hpp"
#include "archet/physics/simulation.hpp"

namespace archet {

double Simulation::position(MatSlot s) const {
    const CompiledLevel& lv = model_.levels[s.level];
    const int derived = lv.derived_point_of[s.index];
    return derived < 0 ? lv.x()[s.index] : modal_point_position(lv.derived_points[derived], lv.x());
}

double Simulation::velocity(MatSlot s) const {
    const CompiledLevel& lv = model_.levels[s.level];
    const int derived = lv.derived_point_of[s.index];
    if (derived < 0) return stored_velocity(s);
    const CompiledModalPoint& p = lv.derived_points[derived];
    return (modal_point_position(p, lv.x()) - modal_point_position(p, lv.x_prev())) / lv.dt;
}

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
        case ProbeKind::Position:  // (a MAT a probe reads is stepped)
            return stored_position(p.mat);
        case ProbeKind::Velocity:
            return stored_velocity(p.mat);
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
