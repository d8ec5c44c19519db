#pragma once
// What a level's step adds to the chain loop's update besides the chain, and the totals it keeps
// of the watched MATs: shared by integrate() and the bowed chain's loop, which hold the level's
// arrays each its own way (the loop in its frame, read once per block). Private to the physics
// sources.

#include <algorithm>
#include <cstddef>
#include <span>

#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/modal_point_position.hpp"

namespace archet::level_forces {

/// The forces of the level's links other than its chain's (a body's bridge, a contact), from
/// x[n] and x[n−1], onto `ext`.
[[gnu::always_inline]] inline void add_link_forces(const CompiledLevel& lv, const double* x,
                                                   const double* xp, double* ext) {
    for (const CompiledLink& l : lv.links) {
        const double d = x[l.a] - x[l.b];
        const double dp = xp[l.a] - xp[l.b];
        double f = l.k * (d - l.length) + l.zdt * (d - dp);
        if (l.contact) f = (d - l.length > 0.0) ? std::max(f, 0.0) : 0.0;
        ext[l.a] -= f;
        ext[l.b] += f;
    }
}

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

/// A modal point where its modes put it.
[[gnu::always_inline]] inline void follow_modes(const CompiledModalPoint& point, double* xn) {
    xn[point.index] = modal_point_position(point, xn);
}

/// Every modal point where its modes put it.
[[gnu::always_inline]] inline void follow_modes(std::span<const CompiledModalPoint> points,
                                                double* xn) {
    for (const CompiledModalPoint& p : points) follow_modes(p, xn);
}

/// Each modal point's force moves its modes.
[[gnu::always_inline]] inline void move_points_modes(std::span<const CompiledModalPoint> points,
                                                     const double* c, const double* ext,
                                                     const double* held, double* xn) {
    for (const CompiledModalPoint& p : points) {
        const double force = ext[p.index] + held[p.index];
        if (force != 0.0) add_modal_force(p, c, xn, force);
    }
}

/// The modal points' share of the update: each point's force moves its modes, then every point
/// follows its modes.
[[gnu::always_inline]] inline void move_modal_points(std::span<const CompiledModalPoint> points,
                                                     const double* c, const double* ext,
                                                     const double* held, double* xn) {
    move_points_modes(points, c, ext, held, xn);
    follow_modes(points, xn);
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
