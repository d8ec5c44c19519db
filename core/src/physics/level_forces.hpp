#pragma once
// What a level's step adds to the chain loop's update besides the chain, and the totals it keeps
// of the watched MATs: shared by integrate() and the bowed chain's loop, which hold the level's
// arrays each its own way (the loop in its frame, read once per block). Private to the physics
// sources.

#include <cstddef>
#include <span>

#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/compiled_model.hpp"

namespace archet::level_forces {

/// The forces of the chain links something reads this step (a watched MAT's total, a probe):
/// the chain loop folds the others into the update without keeping them.
[[gnu::always_inline]] inline void recompute_used_chain_forces(std::span<const int> used,
                                                               const CompiledLevel& lv,
                                                               const double* x, const double* xp,
                                                               double* chain_force) {
    for (int j : used) chain_force[j] = chain_link_force(lv, x, xp, j);
}

/// The update is linear in force, so the other forces add their share afterwards, only where
/// there are any: the other links' (`external`) and the held forces of slower links.
[[gnu::always_inline]] inline void add_touched(std::span<const int> touched, const double* c,
                                               const double* ext, const double* held, double* xn) {
    for (int s : touched) xn[s] += c[s] * (ext[s] + held[s]);
}

/// The coefficients of a level's springs and dampers to ground, by storage index.
struct GroundArrays {
    const double *k, *zdt, *rest;
};

/// What the grounds the chain loop did not take pull off the update.
[[gnu::always_inline]] inline void pull_grounds(std::span<const CompiledGround> grounds,
                                                const double* x, const double* xp, const double* c,
                                                GroundArrays g, double* xn) {
    for (const CompiledGround& ground : grounds) {
        const int s = ground.index;
        xn[s] -= ground_pull(x[s], xp[s], c[s], g.k[s], g.zdt[s], g.rest[s]);
    }
}

/// Each watched MAT's total force this step, once every force on it is known.
[[gnu::always_inline]] inline void sum_watched(std::span<const int> watched, const double* ext,
                                               const double* held, const double* chain_force,
                                               double* watched_force) {
    for (std::size_t w = 0; w < watched.size(); ++w)
        watched_force[w] = watched_total(ext, held, chain_force, watched[w]);
}

/// The other forces start the next step from nothing.
[[gnu::always_inline]] inline void clear_touched(std::span<const int> touched, double* ext) {
    for (int s : touched) ext[s] = 0.0;
}

}  // namespace archet::level_forces
