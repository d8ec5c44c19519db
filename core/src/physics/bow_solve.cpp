// The bow module's friction at each of its level's steps: one member of Simulation, in a file
// of its own because it is the one non-linear solve of the scheme.
#include "archet/physics/simulation.hpp"

#include <algorithm>
#include <cmath>

namespace archet {

namespace {

// a / b, or a times 1/b computed beside the solve, off its path (the form since revision 4).
template <bool kDivides>
[[gnu::always_inline]] inline double over(double a, double b, double inverse_b) {
    if constexpr (kDivides)
        return a / b;
    else
        return a * inverse_b;
}

struct Friction {
    double force = 0.0;       ///< F, on the string
    double dissipated = 0.0;  ///< over the step
    bool sticking = false;
};

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
// For normal force n > 0. From revision 4 on it multiplies by 1/csum and 1/T, which wait for
// nothing the step computes: dividing put a division, several times a product's latency, on
// the path from the predicted motion to the force.
template <bool kDivides>
Friction solve_friction(const CompiledBow& bow, double n, double csum, double u_free, double u_prev,
                        double dt, double inverse_dt) {
    const double inverse_csum = 1.0 / csum;
    Friction out;
    const double f_target = over<kDivides>(u_free, csum, inverse_csum);
    const double f_passive = over<kDivides>(u_free + u_prev, csum, inverse_csum);
    const double f_stick = std::clamp(f_target, std::min(0.0, f_passive), std::max(0.0, f_passive));
    if (std::abs(f_stick) <= bow.mu_s * n) {
        out.force = f_stick;
        out.sticking = true;
        // F·(u+ + u−)/2 with u+ = ufree − F·csum, written so that rounding cannot flip
        // its sign: F and (F_passive − F) share the sign of F_passive.
        out.dissipated = 0.5 * f_stick * csum * (f_passive - f_stick);
        return out;
    }
    const double w_free = 0.5 * (u_free + u_prev);
    const double q_free = over<kDivides>(std::abs(w_free), dt, inverse_dt);
    const double alpha = over<kDivides>(n * csum, 2.0 * dt, 0.5 * inverse_dt);
    const double b = bow.v0 + alpha * bow.mu_d - q_free;
    const double cq = bow.v0 * (alpha * bow.mu_s - q_free);  // < 0 when slipping
    const double root = std::sqrt(b * b - 4.0 * cq);
    const double q = b > 0.0 ? -2.0 * cq / (b + root) : 0.5 * (root - b);
    const double mu = bow.mu_d + (bow.mu_s - bow.mu_d) * bow.v0 / (bow.v0 + q);
    out.force = std::copysign(n * mu, w_free);
    out.dissipated = n * mu * q * dt;  // |F|·|w|·T, w the mid-step velocity
    return out;
}

}  // namespace

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
    const double inverse_dt = 1.0 / lv.dt;  // for the solve and the slip velocity alike
    Friction friction;
    if (n > 0.0)
        friction = friction_divides_
                       ? solve_friction<true>(bow, n, csum, u_free, u_prev, lv.dt, inverse_dt)
                       : solve_friction<false>(bow, n, csum, u_free, u_prev, lv.dt, inverse_dt);
    const double f = friction.force;
    bow.sticking = friction.sticking;
    bow.dissipated = friction.dissipated;
    push(lv, bow.string, f);
    push(lv, bow.bow, -f);
    lv.external[bow.string] += f;
    lv.external[bow.bow] -= f;
    const double u_next = u_free - f * csum;
    bow.friction = f;
    bow.slip_velocity = friction_divides_ ? u_next / lv.dt : u_next * inverse_dt;
}

}  // namespace archet
