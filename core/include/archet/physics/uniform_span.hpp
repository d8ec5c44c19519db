#pragma once
// The runs of a level's MATs whose chain-loop coefficients are all alike: each homogeneous
// string or chain between its ends. The chain loop and the stored energy read them once for a
// whole run rather than seven arrays a MAT, which halves what a long chain moves through the
// caches; the result is the same bits, since the values are the same.

#include <cstddef>
#include <span>
#include <vector>

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

/// The coefficients the chain loop broadcasts, each already in every lane of a vector of eight:
/// it loads them as they are. (GCC builds the broadcast of a struct's field, in a loop over the
/// runs, one masked lane at a time: eight instructions rather than one.)
struct ChainLanes {
    alignas(64) double k[8], zdt[8], length[8], c[8], a[8], b[8], e[8];
};

/// The rounds of W MATs of the chain loop (they start at storage 1 + W·r) that lie wholly
/// inside the run first … last: it broadcasts their coefficients. [begin, end), both of the
/// form 1 + W·r; begin == end for an empty run or one too short to hold a round.
struct SharedRounds {
    int begin, end;
};
constexpr SharedRounds shared_rounds(int first, int last, int W) {
    const int begin = 1 + W * ((first - 1 + W - 1) / W);  // the first round from `first` on
    const int end = 1 + W * (last / W);                   // the first that would pass `last`
    return {begin, end > begin ? end : begin};
}

/// MATs first … last (storage indices) that share their coefficients, `shared`.
struct UniformSpan {
    UniformSpan() = default;
    UniformSpan(int first, int last, const ChainCoefficients& shared);
    /// MATs first … last of this run.
    UniformSpan part(int first, int last) const;
    int length() const { return last - first + 1; }
    /// The run's rounds of W = 2, 4 or 8 MATs, found once rather than at every step.
    SharedRounds rounds(int W) const { return rounds_[W == 8 ? 2 : W == 4 ? 1 : 0]; }

    int first = 1, last = 0;  ///< set by the constructor or part(), which find the rounds
    ChainCoefficients shared;
    ChainLanes lanes{};  ///< `shared` as the chain loop reads it

  private:
    SharedRounds rounds_[3]{};
};

/// A level's runs of alike MATs, in storage order and disjoint: one for each string of an
/// instrument, and a MAT changed while playing splits its run in two. Their storage is made
/// once, for kCapacity runs, so that a split on the real-time thread never allocates (a copy
/// keeps it whole); it lives on the heap, as it is large and read once a step.
class UniformRuns {
  public:
    static constexpr int kCapacity = 8;
    /// Shorter runs are not kept: they could not hold a whole round of the widest loop.
    static constexpr int kShortest = 8;

    UniformRuns() = default;
    // Copied even when moved: a moved-from vector would be empty, and the next split or find
    // would write past it.
    UniformRuns(const UniformRuns&) = default;
    UniformRuns& operator=(const UniformRuns&) = default;

    std::span<const UniformSpan> all() const {
        return {run_.data(), static_cast<std::size_t>(count_)};
    }
    int count() const { return count_; }
    const UniformSpan& operator[](int i) const { return run_[i]; }

    void clear() { count_ = 0; }
    /// Adds a run after every run kept, if at least kShortest long: when they are all taken,
    /// it replaces the shortest one (the last of those as short) if it is longer.
    void keep(const UniformSpan& run);
    /// Run i loses MAT s: it becomes its two sides, each kept if at least kShortest long (only
    /// the longer one when there is no room for both).
    void split(int i, int s);

  private:
    void remove(int i);

    std::vector<UniformSpan> run_ = std::vector<UniformSpan>(kCapacity);
    int count_ = 0;
};

/// Sets level.uniform to the level's runs of alike MATs: the kCapacity longest (the first ones,
/// if several are as long) of those of at least kShortest. O(MATs) and no allocation: at
/// compile time, when a state is loaded (a model swap, on the real-time thread too) and after
/// a batch of live changes (Simulation::refresh_uniform_runs()).
void find_uniform_runs(CompiledLevel& level);

/// After MAT s's coefficients (its mass, ground or chain link to s + 1) changed while playing:
/// if s no longer matches its run, the run is split around it into the two sides, each kept if
/// long enough (only the longer one when there is no room for both). Constant time (at most
/// kCapacity runs are moved), real-time safe.
void split_uniform_run(CompiledLevel& level, int s);

}  // namespace archet
