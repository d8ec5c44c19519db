// The bow module's friction at each of its level's steps (friction_solve.hpp solves it).
#include "archet/physics/simulation.hpp"

#include "friction_solve.hpp"

namespace archet {

void Simulation::solve_bow(CompiledLevel& lv, CompiledBow& bow) {
    const double* x = lv.x();
    const double* xn = lv.x_next();
    const double* xp = lv.x_prev();
    const int b = bow.bow, s = bow.string;
    const double f = friction::solve_point_bow(
        bow, {x[b], xp[b], xn[b], response(lv, b), x[s], xp[s], xn[s], response(lv, s)}, lv.dt,
        1.0 / lv.dt, friction_divides_);
    push_pair(lv, s, f, b, -f);
    lv.external[s] += f;
    lv.external[b] -= f;
}

}  // namespace archet
