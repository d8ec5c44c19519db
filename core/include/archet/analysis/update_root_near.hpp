#pragma once
// One root of the scheme's update near a guess, without the dense solve of all of them: what a
// tuning loop needs to look at one mode (seconds saved per look on a long string).

#include <complex>
#include <optional>
#include <span>

#include "archet/model/linear_system.hpp"

namespace archet {

/// The root z of the system's one-step update (an eigenvalue of update_matrix()) nearest
/// `guess`, found on the quadratic problem P(z)·x = ((z − 1)²·M + z·T²·K + (z − 1)·T·Z)·x = 0
/// (by an O(n) solve on a chain, a sparse LU elsewhere): inverse iteration from `guess`, then the
/// shift moved to each new estimate (P is complex symmetric, so xᵀ·P(z)·x = 0 gives z to about the
/// square of the shape's error). The iteration starts from `start` (a shape near the mode's, one
/// entry per DOF), or from a ramp. The guess itself when P is singular there to the last bit.
/// Nothing for a system with fingers (their correction is not in P) or when the iteration does not
/// settle; a caller that must be sure of the mode checks it against update_roots().
std::optional<std::complex<double>> update_root_near(const LinearSystem& system,
                                                     std::complex<double> guess,
                                                     std::span<const double> start = {});

}  // namespace archet
