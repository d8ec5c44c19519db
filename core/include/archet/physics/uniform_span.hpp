#pragma once
// The run of a level's MATs whose chain-loop coefficients are all alike: a homogeneous string
// or chain between its ends. The chain loop and the stored energy read them once for the whole
// run rather than seven arrays a MAT, which halves what a long chain moves through the caches;
// the result is the same bits, since the values are the same.

namespace archet {

struct CompiledLevel;

/// Every coefficient the chain loop and the stored energy read for MAT s: T²/m and the mass,
/// the chain link from s to s + 1 (K, Z/T, rest length), the ground (K, Z/T, rest position)
/// and the ground folded into the update (a, b, e; see fold_ground()).
struct ChainCoefficients {
    double c = 0, mass = 0, k = 0, zdt = 0, length = 0;
    double ground_k = 0, ground_zdt = 0, rest = 0, a = 0, b = 0, e = 0;
    bool operator==(const ChainCoefficients&) const;  ///< bit for bit
};

/// The longest run of MATs first … last (storage indices) that share their coefficients,
/// `shared`. Empty when last < first.
struct UniformSpan {
    int first = 1, last = 0;
    ChainCoefficients shared;
};

/// Sets level.uniform to the longest run of MATs with equal coefficients (the first, if
/// several are as long). O(MATs) and no allocation: at compile time, when a state is loaded
/// (a model swap, on the real-time thread too) and after a batch of live changes
/// (Simulation::refresh_uniform_spans()).
void find_uniform_span(CompiledLevel& level);

/// After MAT s's coefficients (its mass, ground or chain link to s + 1) changed while playing:
/// if s no longer matches the run, the run keeps the longer side of it. O(1), real-time safe.
void narrow_uniform_span(CompiledLevel& level, int s);

}  // namespace archet
