// The bow module's friction at each of its level's steps: one member of Simulation, in a file
// of its own because it is the one non-linear solve of the scheme.
#include "archet/physics/simulation.hpp"

#include <algorithm>
#include <cmath>

namespace archet {

// The bow–string friction, solved on the predicted motion so that it is stable for any
// sharpness of the curve, and strictly passive in the scheme's own energy. Units below are
// displacement per step (u = v·T); c = T²/m.
//   u−     relative motion bow − string over the last step
//   ufree  relative motion over the next step without friction
//   F      friction on the string (−F on the bow): u+ = ufree − F·csum
// The energy the friction takes over a step is F·(u+ + u−)/2; it must never be negative.
// Stick: F closest to ufree/csum (u+ = 0) within [0, (ufree + u−)/csum], the passive range,
//        when |F| ≤ μs·N.
// Slip:  F = N·μ(|w|)·sign(w) at the mid-step velocity w = (u+ + u−)/(2T); with the
//        hyperbolic curve μ(q) = μd + (μs − μd)·v0/(v0 + q) this is a quadratic in |w| with
//        exactly one positive root.
void Simulation::solve_bow(CompiledLevel& lv, CompiledBow& bow) {
    const double* x = lv.x();
    const double* xp = lv.x_prev();
    double* xn = lv.x_next();
    // How far each side moves per newton over the step: T²/m, or its modes' for a modal point.
    const double cb = response(lv, bow.bow), cs = response(lv, bow.string);
    const double csum = cb + cs;
    const double u_prev = (x[bow.bow] - xp[bow.bow]) - (x[bow.string] - xp[bow.string]);
    const double u_free = (xn[bow.bow] - x[bow.bow]) - (xn[bow.string] - x[bow.string]);
    const double n = bow.normal;
    double f = 0.0;
    bow.sticking = false;
    bow.dissipated = 0.0;
    if (n > 0.0) {
        const double f_target = u_free / csum;
        const double f_passive = (u_free + u_prev) / csum;
        const double f_stick =
            std::clamp(f_target, std::min(0.0, f_passive), std::max(0.0, f_passive));
        if (std::abs(f_stick) <= bow.mu_s * n) {
            f = f_stick;
            bow.sticking = true;
            // F·(u+ + u−)/2 with u+ = ufree − F·csum, written so that rounding cannot flip
            // its sign: F and (F_passive − F) share the sign of F_passive.
            bow.dissipated = 0.5 * f * csum * (f_passive - f);
        } else {
            const double w_free = 0.5 * (u_free + u_prev);
            const double q_free = std::abs(w_free) / lv.dt;
            const double alpha = n * csum / (2.0 * lv.dt);
            const double b = bow.v0 + alpha * bow.mu_d - q_free;
            const double cq = bow.v0 * (alpha * bow.mu_s - q_free);  // < 0 when slipping
            const double root = std::sqrt(b * b - 4.0 * cq);
            const double q = b > 0.0 ? -2.0 * cq / (b + root) : 0.5 * (root - b);
            const double mu = bow.mu_d + (bow.mu_s - bow.mu_d) * bow.v0 / (bow.v0 + q);
            f = std::copysign(n * mu, w_free);
            bow.dissipated = n * mu * q * lv.dt;  // |F|·|w|·T, w the mid-step velocity
        }
    }
    push(lv, bow.string, f);
    push(lv, bow.bow, -f);
    lv.external[bow.string] += f;
    lv.external[bow.bow] -= f;
    const double u_next = u_free - f * csum;
    bow.friction = f;
    bow.slip_velocity = u_next / lv.dt;
}

}  // namespace archet
