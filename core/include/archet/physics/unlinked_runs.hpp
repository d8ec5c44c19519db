#pragma once
// The runs of a level's MATs that no chain link joins to their neighbours: the modes of a string
// in modal form, a body's modes. The chain loop moves each by its own update alone (its ground,
// folded), without the forces of the links on either side, which are ±0 for them: a few
// multiply-adds a MAT rather than the links' shuffles and products, and the same bits while the
// motion is finite.
//
// Why the same bits: the chain's update adds T²/m·(f_left − f_right), a zero, to the MAT's own
// update ((a·x + b·x⁻) + e), which leaves every value as it is but −0 (−0 + (+0) is +0). A sum
// p + e is −0 only where both are, or, on a thread that flushes subnormal results to zero (the
// render threads do: DenormalGuard), where it falls below the smallest normal; neither can
// happen while e is +0 or at least 2^−969 in size, which is every e but those of a rest of −0,
// of a ground with no stiffness and a rest below 0, or of a rest within some 1e−290 m of 0. Each
// run counts its MATs with such an e (`zero_prone_rests`) and is left to the chain's rounds while
// it has any. (Motion no longer finite differs too: 0·∞ is NaN in a link, not in an own update.)

#include <vector>

#include "archet/physics/uniform_span.hpp"

namespace archet {

struct CompiledLevel;

/// MATs first … last (storage indices) with no chain link on either side, all before the fixed
/// tail that the chain loop leaves alone.
struct UnlinkedRun {
    /// Shorter runs are left in the chain's rounds: stepping out of them and back costs more
    /// than a round or two saves (the shipped strings' nine unlinked MATs, a body's six modes
    /// and the bow's two, took 5 % longer in one round of their own).
    static constexpr int kShortest = 32;

    int first = 1, last = 0;
    /// How many of its MATs have a folded e (fold_ground()) that may leave their own update at
    /// −0 (may_leave_negative_zero()): the chain loop moves them alone only while there are none.
    int zero_prone_rests = 0;
    bool moves_alone() const { return zero_prone_rests == 0; }
    /// Its rounds of W = 2, 4 or 8 MATs (shared_rounds()).
    SharedRounds rounds(int W) const { return shared_rounds(first, last, W); }
};

/// The runs of at least UnlinkedRun::kShortest unlinked MATs, in storage order, on a level whose
/// grounds are folded and taken by the chain loop (grounds_in_chain_loop()): without a ground,
/// a MAT's own update is −0 wherever it is at −0. A chain link counts as absent when no element of
/// the model stands behind it and its coefficients are zero. Found when the level is compiled:
/// nothing played can link two MATs or give an absent link a stiffness (no parameter names it).
std::vector<UnlinkedRun> find_unlinked_runs(const CompiledLevel& lv);

/// After a state is loaded and the grounds folded again: drops the runs it has linked (a state
/// is all numbers, an absent link's among them) and counts their zero-prone rests again. In place,
/// as a hand-over on the real-time thread loads states.
void recheck_unlinked_runs(CompiledLevel& lv);

/// After MAT s's ground is folded again (a live change of its ground or its mass), whose e was
/// zero-prone before if `was_zero_prone`: its run's count, in constant time on the real-time
/// thread (a glide may change every mode of a string at every block).
void refolded_unlinked(CompiledLevel& lv, int s, bool was_zero_prone);

/// Whether a MAT's own update ((a·x + b·x⁻) + e) may be −0 for some motion: e is not +0 and
/// smaller than 2^−969 in size (−0, a subnormal, a tiny rest's).
bool may_leave_negative_zero(double e);

}  // namespace archet
