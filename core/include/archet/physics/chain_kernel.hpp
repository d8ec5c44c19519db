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

/// The scheme's new position of a MAT from the forces of its two chain links,
/// 2x − x⁻ + T²/m·(f_left − f_right), for a double or a vector of them: the chain loop and
/// the MATs updated again after it (Simulation::integrate) must agree to the bit.
template <class T>
[[gnu::always_inline]] inline T chain_update(T x, T xp, T c, T left, T right) {
    return 2.0 * x - xp + c * (left - right);
}

/// What an oscillator's spring and damper to ground take off that update (zero for a MAT
/// without them).
template <class T>
[[gnu::always_inline]] inline T ground_pull(T x, T xp, T c, T k, T z, T rest) {
    return c * (k * (x - rest) + z * (x - xp));
}

/// Whether the chain loop also takes the level's grounds: when most MATs have one (a string
/// with losses to its rest points); a few bridges do not repay the loop's extra flops.
inline bool grounds_in_chain_loop(const CompiledLevel& level) {
    return 2 * level.grounds.size() > static_cast<std::size_t>(level.size);
}

/// Writes x[n+1] of every MAT of the level into `xn` from its chain links (and its grounds,
/// see grounds_in_chain_loop()), and each chain link's force into `chain_force`.
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
