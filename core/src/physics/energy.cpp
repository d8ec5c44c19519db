// The scheme's energy books, Simulation's members: what each damper and the bow took over a
// step, what is stored, and what the hands put in.
#include "archet/physics/simulation.hpp"

#include <algorithm>
#include <cmath>

#include "archet/physics/chain_kernel.hpp"

namespace archet {

void Simulation::account(CompiledLevel& lv) {
    const double* x = lv.x();
    const double* xp = lv.x_prev();
    const double* xn = lv.x_next();
    // A damper Z takes Z·T·v² over a step, v the centred velocity (x[n+1] − x[n−1])/2T: with
    // the damper's in-flight term in stored_energy() this closes the books exactly.
    auto taken = [&](double zdt, int a, int b) {
        const double centred = (xn[a] - xn[b]) - (xp[a] - xp[b]);
        return 0.25 * zdt * centred * centred;
    };
    const std::size_t lias = model_.source.lias.size();
    // The chain's and the grounds' dampers a run of elements at a time: each element takes the
    // same term as one at a time would give it, and the runs' loops vectorise.
    const double* __restrict const chain_zdt = lv.chain_zdt.data();
    for (const ElementRun& run : lv.chain_element_runs) {
        double* __restrict const taken_by = dissipated_.data() + run.element;
        for (int j = run.begin; j < run.end; ++j)
            taken_by[j - run.begin] += taken(chain_zdt[j], j, j + 1);
    }
    const double* __restrict const ground_zdt = lv.ground_zdt.data();
    for (const ElementRun& run : lv.ground_runs) {
        double* __restrict const taken_by = dissipated_.data() + lias + run.element;
        for (int s = run.begin; s < run.end; ++s)
            taken_by[s - run.begin] += 0.25 * ground_zdt[s] * (xn[s] - xp[s]) * (xn[s] - xp[s]);
    }
    for (const auto& l : lv.links) {
        if (l.contact && x[l.a] - x[l.b] - l.length <= 0.0) continue;
        dissipated_[l.element] += taken(l.zdt, l.a, l.b);
    }
    for (int b : lv.bows) {
        const CompiledBow& bow = model_.bows[b];
        const double p = x[bow.press] - x[bow.surface];
        double buffer = 0;
        if (p > 0.0 && bow.normal > 0.0) buffer = taken(bow.zbdt, bow.press, bow.surface);
        dissipated_[bow.element] += bow.dissipated + buffer;
    }
    for (int f : lv.fingers)
        dissipated_[model_.fingers[f].element] += finger_dissipation(lv, model_.fingers[f]);
}

double Simulation::hand_work() const {
    // The newest force's half of the move the hand links will see at their next tick.
    double pending = 0;
    for (int i = 0; i < model_.hand_links; ++i) {
        const CompiledCrossLink& l = model_.cross_links[i];
        pending +=
            l.hand_sign * 0.5 * l.force *
            (seen_position(l.hand_slot, CompiledCrossLink::EndRate::Slower, true) - l.hand_seen);
    }
    return hand_work_ + pending;
}

double Simulation::stored_energy() const {
    // Kinetic ½m((x[n]−x[n−1])/T)², ½K·d[n]·d[n−1] per spring, and −(Z/4T)·(d[n]−d[n−1])² per
    // damper: the energy a backward-difference damper has taken in but not yet lost. With it,
    // a step's dissipation is Z·T·v² of the centred velocity, never negative, so the books
    // close at every step whatever the hand does.
    double e = 0;
    for (const auto& lv : model_.levels) {
        const double* x = lv.x();
        const double* xp = lv.x_prev();
        auto in_flight = [&](double zdt, int a, int b) {
            const double u = (x[a] - x[b]) - (xp[a] - xp[b]);
            return 0.25 * zdt * u * u;
        };
        e += level_stored_energy(lv);  // masses, chain links and grounds
        for (const auto& l : lv.links) {
            const double d = x[l.a] - x[l.b] - l.length, dp = xp[l.a] - xp[l.b] - l.length;
            if (!l.contact || (d > 0 && dp > 0)) e += 0.5 * l.k * d * dp;
            if (!l.contact || d > 0) e -= in_flight(l.zdt, l.a, l.b);
        }
        for (int b : lv.bows) {
            const auto& bow = model_.bows[b];
            const double p = x[bow.press] - x[bow.surface], pp = xp[bow.press] - xp[bow.surface];
            if (p > 0 && pp > 0) e += 0.5 * bow.kb * p * pp;
            if (p > 0) e -= in_flight(bow.zbdt, bow.press, bow.surface);
        }
        for (int f : lv.fingers) e += finger_stored_energy(lv, model_.fingers[f]);
    }
    for (const auto& l : model_.cross_links) {
        const double d =
            seen_position(l.a, l.a_rate, true) - seen_position(l.b, l.b_rate, true) - l.length;
        const double dp = l.d_prev - l.length;
        if (!l.contact || (d > 0 && dp > 0)) e += 0.5 * l.k * d * dp;
        if (!l.contact || d > 0) e -= 0.25 * l.zdt * (d - dp) * (d - dp);
    }
    return e;
}

}  // namespace archet
