#pragma once
// The bow module's pressure buffer and bow–string friction solve, shared by the general step
// (simulation.cpp, bow_solve.cpp) and the bowed chain's (simulation_bowed_chain.cpp). Private
// to the physics sources.

#include <algorithm>
#include <cmath>

#include "archet/physics/compiled_model.hpp"

namespace archet::friction {

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
inline Friction solve_friction(const CompiledBow& bow, double n, double csum, double u_free,
                               double u_prev, double dt, double inverse_dt) {
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

/// The normal force of the bow's pressure buffer from where its press and the surface are now
/// and a step before: a one-sided spring-damper, zero while they are apart or pulling.
[[gnu::always_inline]] inline double pressure_buffer_normal(const CompiledBow& bow, const double* x,
                                                            const double* xp) {
    const double p = x[bow.press] - x[bow.surface];
    const double pp = xp[bow.press] - xp[bow.surface];
    return p > 0.0 ? std::max(0.0, bow.kb * p + bow.zbdt * (p - pp)) : 0.0;
}

/// Where a bow's two MATs are (x[n], x[n−1]) and would be after the step without the friction
/// (x[n+1] predicted), and how far each moves per newton over it (T²/m, or a modal point's).
struct BowMotion {
    double bow, bow_prev, bow_next, bow_response;
    double string, string_prev, string_next, string_response;
};

/// Solves the bow's friction on that motion and keeps what the bow reports of it (the force,
/// sticking, the dissipation, the slip velocity after the step); returns the force on the string
/// (the bow takes its opposite). Before revision 4 it divides where it now multiplies.
/// `inverse_dt` is 1.0 / dt (the bowed chain's loop computes it once per block).
inline double solve_point_bow(CompiledBow& bow, const BowMotion& m, double dt, double inverse_dt,
                              bool divides) {
    const double csum = m.bow_response + m.string_response;
    const double u_prev = (m.bow - m.bow_prev) - (m.string - m.string_prev);
    const double u_free = (m.bow_next - m.bow) - (m.string_next - m.string);
    const double n = bow.normal;
    Friction friction;
    if (n > 0.0)
        friction = divides ? solve_friction<true>(bow, n, csum, u_free, u_prev, dt, inverse_dt)
                           : solve_friction<false>(bow, n, csum, u_free, u_prev, dt, inverse_dt);
    const double f = friction.force;
    bow.sticking = friction.sticking;
    bow.dissipated = friction.dissipated;
    const double u_next = u_free - f * csum;
    bow.friction = f;
    bow.slip_velocity = divides ? u_next / dt : u_next * inverse_dt;
    return f;
}

}  // namespace archet::friction
