#pragma once
// The loops over every MAT of a rate level: the chain loop (every chain link's force and
// every MAT's update, the bulk of a step) and the stored energy of the level's masses, chain
// links and grounds. Built for several instruction sets that all give the same bits.

#include "archet/physics/compiled_model.hpp"

namespace archet {

enum class ChainBuild { Plain, Avx2, Avx512 };

/// The widest build this CPU runs, chosen once when the library loads.
ChainBuild chosen_chain_build();
bool chain_build_runs_here(ChainBuild build);
const char* chain_build_name(ChainBuild build);  ///< "plain", "avx2", "avx512"

/// The force of a chain link from the distance d = x[j] − x[j+1] now and dp a step before,
/// for a double or a vector of them. Without rest lengths the loop skips `d − length`, which
/// gives the same bits as subtracting a zero length.
template <bool kWithLength, class T>
[[gnu::always_inline]] inline T link_force(T d, T dp, T k, T z, T length) {
    if constexpr (kWithLength)
        return k * (d - length) + z * (d - dp);
    else
        return k * d + z * (d - dp);
}

/// The force of chain link j (joining storage j and j + 1) at this step, as the chain loop
/// computes it; the loop keeps none of them, so the few the step needs beside it (on either
/// side of the watched MATs) are computed again here.
inline double chain_link_force(const CompiledLevel& lv, const double* x, const double* xp, int j) {
    return link_force<true>(x[j] - x[j + 1], xp[j] - xp[j + 1], lv.chain_k[j], lv.chain_zdt[j],
                            lv.chain_length[j]);
}

/// The total force on a watched MAT s this step: the other links' (`external`), the held forces
/// of slower links, and its two chain links' (`chain_force`, link j joining s and s + 1).
inline double watched_total(const double* external, const double* held, const double* chain_force,
                            int s) {
    return external[s] + held[s] + chain_force[s - 1] - chain_force[s];
}

/// The scheme's new position of a MAT from the forces of its two chain links,
/// 2x − x⁻ + T²/m·(f_left − f_right), for a double or a vector of them (every build of the
/// chain loop computes it in this order).
template <class T>
[[gnu::always_inline]] inline T chain_update(T x, T xp, T c, T left, T right) {
    return 2.0 * x - xp + c * (left - right);
}

/// What an oscillator's spring and damper to ground take off that update (zero for a MAT
/// without them), on a level whose chain loop leaves its grounds to the step.
template <class T>
[[gnu::always_inline]] inline T ground_pull(T x, T xp, T c, T k, T z, T rest) {
    return c * (k * (x - rest) + z * (x - xp));
}

/// The new position of a MAT with its ground folded into a, b and e (fold_ground()),
/// ((a·x + b·x⁻) + e) + T²/m·(f_left − f_right), for a double or a vector of them: the update
/// of the chain loop of a level that takes its grounds.
template <class T>
[[gnu::always_inline]] inline T grounded_update(T x, T xp, T a, T b, T e, T c, T left, T right) {
    return ((a * x + b * xp) + e) + c * (left - right);
}

/// Folds MAT s's spring and damper to ground into its update: 2x − x⁻ − T²/m·(K(x − rest) +
/// Z/T(x − x⁻)) is a·x + b·x⁻ + e with a = (2 − T²/m·K) − T²/m·Z/T, b = T²/m·Z/T − 1 and
/// e = T²/m·K·rest (a MAT without a ground: 2, −1, 0). The same update up to rounding, in seven
/// operations a MAT instead of twelve; call it again whenever T²/m or the ground changes (and
/// then split_uniform_run(), as for any change of the chain loop's coefficients).
void fold_ground(CompiledLevel& level, int s);
/// fold_ground() for every MAT of the level.
void fold_grounds(CompiledLevel& level);

/// Whether the chain loop also takes the level's grounds: when most MATs it steps have one (a
/// string with losses to its rest points); a few bridges do not repay the loop's extra flops.
inline bool grounds_in_chain_loop(const CompiledLevel& level) {
    return 2 * level.grounds.size() > static_cast<std::size_t>(level.size - level.derived_after);
}

/// Writes x[n+1] of every MAT of the level into `xn` from its chain links (and its grounds,
/// see grounds_in_chain_loop()).
void integrate_chain(CompiledLevel& level, double* xn);
/// The same with a given build, which must run here (for tests and benchmarks).
void integrate_chain(CompiledLevel& level, double* xn, ChainBuild build);

/// Kinetic energy of the level's MATs plus the energy stored in its chain links and grounds
/// (J), in the discrete-consistent form of Simulation::stored_energy(): summed over the MATs
/// in eight interleaved partial sums, then added in a fixed tree.
double level_stored_energy(const CompiledLevel& level);
/// The same with a given build, which must run here (for tests).
double level_stored_energy(const CompiledLevel& level, ChainBuild build);

}  // namespace archet
