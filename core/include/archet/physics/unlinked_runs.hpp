#pragma once
// The runs of a level's MATs that no chain link joins to their neighbours: the modes of a string
// in modal form, a body's modes. The chain loop moves each by its own update alone (its ground,
// folded), without the forces of the links on either side, which are ±0 for them: a few
// multiply-adds a MAT rather than the links' shuffles and products, and the same bits while the
// motion is finite.
//
// Why the same bits: the chain's update adds T²/m·(f_left − f_right), a zero, to the MAT's own
// update ((a·x + b·x⁻) + e), which leaves every value as it is but −0 (−0 + (+0) is +0). The own
// update is −0 only where a·x + b·x⁻ and e both are: never while no e is −0, which each run
// keeps track of (`moves_alone`). (Motion no longer finite differs: 0·∞ is NaN in a link.)

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
    /// How many of its MATs have a folded e of −0 (fold_ground()): the chain loop moves them
    /// by their own update only while there are none.
    int negative_zero_rests = 0;
    bool moves_alone() const { return negative_zero_rests == 0; }
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
/// is all numbers, an absent link's among them) and counts their −0 rests again. In place, as a
/// hand-over on the real-time thread loads states.
void recheck_unlinked_runs(CompiledLevel& lv);

/// After MAT s's ground is folded again (a live change of its ground or its mass), whose e was
/// −0 before if `was_negative_zero`: its run's count of −0 rests, in constant time on the
/// real-time thread (a glide may change every mode of a string at every block).
void refolded_unlinked(CompiledLevel& lv, int s, bool was_negative_zero);

/// Whether a folded e is −0 (its bits: −0 == +0).
bool is_negative_zero(double e);

}  // namespace archet
