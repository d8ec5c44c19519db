// A finger stopping a string: one member of Simulation, in a file of its own because, like the
// bow, it is solved on the predicted motion rather than in the explicit scheme.
#include "archet/model/finger_contact.hpp"
#include "archet/physics/simulation.hpp"

namespace archet {

namespace {

// Where a finger touches now: between storage a and b, with weights wa + wb = 1.
struct Touch {
    int a, b;
    double wa, wb;
    double at(const double* x) const { return wa * x[a] + wb * x[b]; }
};

Touch touch_of(const CompiledFinger& finger) {
    const FingerContact c = finger_contact(finger.position, finger.along.size());
    return {finger.along[c.first], finger.along[c.first + 1], 1.0 - c.weight, c.weight};
}

}  // namespace

// The finger is a spring k and a damper Z from its contact point to ground, scaled by its
// pressure. Its contact point u is the weighted position of the two MATs it lies between;
// c = (1−w)²·T²/m_a + w²·T²/m_b is how far u moves per newton over a step. The force uses the
// mean of the new and the previous position and the centred velocity (trapezoidal rule):
//   F = −k·(u+ + u−)/2 − (Z/T)·(u+ − u−)/2,   u+ = ufree + c·F,
// one linear equation in F. Its work over a step is exactly −¼k(u+² − u−²) − ¼(Z/T)(u+ − u−)²:
// it stores ¼k(u[n]² + u[n−1]²) and dissipates the rest, so it is passive and stable for any
// stiffness, and a pressed finger can be as stiff as a fingerboard without shortening the step.
void Simulation::solve_finger(CompiledLevel& lv, CompiledFinger& finger) {
    const Touch t = touch_of(finger);
    const double k = finger.pressure * finger.k, zdt = finger.pressure * finger.zdt;
    const double c = t.wa * t.wa * response(lv, t.a) + t.wb * t.wb * response(lv, t.b);
    const double u_free = t.at(lv.x_next());
    const double u_before = t.at(lv.x_prev());
    const double f = -(k * (u_free + u_before) + zdt * (u_free - u_before)) / (2.0 + c * (k + zdt));
    push_pair(lv, t.a, t.wa * f, t.b, t.wb * f);
}

// The finger's stored energy ¼k(u[n]² + u[n−1]²) and, after a step, the energy its damper took
// over it, ¼(Z/T)(u[n+1] − u[n−1])², both at its contact point now.
double Simulation::finger_stored_energy(const CompiledLevel& lv,
                                        const CompiledFinger& finger) const {
    const Touch t = touch_of(finger);
    const double u = t.at(lv.x()), u_before = t.at(lv.x_prev());
    return 0.25 * finger.pressure * finger.k * (u * u + u_before * u_before);
}

double Simulation::finger_dissipation(const CompiledLevel& lv, const CompiledFinger& finger) const {
    const Touch t = touch_of(finger);
    const double* xn = lv.x_next();
    const double moved = t.wa * (xn[t.a] - lv.x_prev()[t.a]) + t.wb * (xn[t.b] - lv.x_prev()[t.b]);
    return 0.25 * finger.pressure * finger.zdt * moved * moved;
}

}  // namespace archet
