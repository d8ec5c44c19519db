#pragma once
// The run of a level's MATs whose chain-loop coefficients are all alike: a homogeneous string
// or chain between its ends. The chain loop reads them once for the whole run rather than
// seven arrays a MAT, which halves what a long chain moves through the caches; the result is
// the same bits, since the values are the same.

#include "archet/physics/compiled_model.hpp"

namespace archet {

/// MAT s's coefficients as the chain loop reads them from the level's arrays.
ChainCoefficients chain_coefficients(const CompiledLevel& level, int s);

/// Sets level.uniform to the longest run of MATs with equal coefficients (the first, if
/// several are as long). O(MATs): for compile time and for a loaded state.
void find_uniform_span(CompiledLevel& level);

/// After MAT s's coefficients (its mass, ground or chain link to s + 1) changed while playing:
/// if s no longer matches the run, the run keeps the longer side of it. O(1), real-time safe;
/// the run does not grow back until the level is compiled or a state is loaded again.
void narrow_uniform_span(CompiledLevel& level, int s);

}  // namespace archet
