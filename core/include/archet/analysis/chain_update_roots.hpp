#pragma once
// All the roots of a chain's one-step update without the dense solve of them: each found from
// its undamped mode (what a harmonic string's tuning reads at each of its corrections, seconds
// saved each on a low string).

#include <complex>
#include <optional>
#include <vector>

#include "archet/model/linear_system.hpp"

namespace archet {

/// The roots of a chain's one-step update with a positive imaginary part, one a mode, each
/// found from its undamped mode: the root of φᵀ·P(z)·φ = 0 with the mode's shape φ is the guess,
/// which update_root_near() refines on the chain in microseconds (the dense solve of all the
/// roots takes seconds on a low string). Nothing unless each root lies nearer its own guess
/// than half way to any other (less a margin for where the refinement stops): then they are as
/// many distinct roots as the update has pairs, so all of them. Nothing too where the system is
/// not a chain, has a finger, or a mode's quadratic φᵀ·P(z)·φ = 0 has no complex pair of roots.
/// (A string's losses move its top partials by more cents than lie between them; the guess from
/// the shape takes that in.)
std::optional<std::vector<std::complex<double>>> chain_update_roots(const LinearSystem& system);

}  // namespace archet
