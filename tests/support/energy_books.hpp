#pragma once
// The energy books of a running simulation, step by step: stored change − (hand work −
// dissipation), which the scheme keeps at round-off (docs/physics.md, "Energy").

#include <algorithm>
#include <cmath>

#include "archet/physics/simulation.hpp"

namespace archet::test {

/// The worst step-by-step imbalance of the books while the bow presses (after the first 2000
/// steps), over `steps` steps; and the largest stored energy, for scale.
struct Books {
    double worst = 0, scale = 0;
};

inline Books step_by_step_books(Simulation& sim, int steps) {
    sim.enable_accounting(true);
    double previous = sim.stored_energy(), dissipated_before = 0, work_before = 0;
    Books books;
    for (int i = 0; i < steps; ++i) {
        sim.step();
        double dissipated = 0;
        for (double d : sim.dissipated_by_element()) dissipated += d;
        const double stored = sim.stored_energy();
        const double balance = (stored - previous) -
                               ((sim.hand_work() - work_before) - (dissipated - dissipated_before));
        // The pressure buffer's contact switching is the only non-conservative term left out.
        if (sim.model().bows[0].normal > 0 && i > 2000)
            books.worst = std::max(books.worst, std::abs(balance));
        books.scale = std::max(books.scale, stored);
        previous = stored, dissipated_before = dissipated, work_before = sim.hand_work();
    }
    return books;
}

}  // namespace archet::test
