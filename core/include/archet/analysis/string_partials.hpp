#pragma once
// The frequencies of a string's partials as analyse_modes() finds them, at a fraction of its
// cost on a chain: each root found from its undamped mode by a few tridiagonal solves, and
// each mode's shape, which tells a partial from a mode of the supports, from a tridiagonal solve
// of its own (what a harmonic string's tuning asks for several times).

#include <complex>
#include <vector>

#include "archet/model/linear_system.hpp"
#include "archet/model/model.hpp"

namespace archet {

/// The frequencies of the modes analyse_modes(system, model) does not call supports, ascending:
/// on a chain, from chain_update_roots() (the dense solve's roots to its own rounding, and the
/// same classes unless a mode's energy is split within rounding of half in the supports), or
/// from the dense solve of the roots where those cannot be told apart; it throws what
/// analyse_modes() throws. Where the system is not a chain (its matrices not tridiagonal in the
/// order of its DOFs) or has a finger, it is analyse_modes() itself.
std::vector<double> string_partial_frequencies(const LinearSystem& system, const Model& model);

/// The shape of the scheme's mode with root z on a tridiagonal system without fingers: a
/// vector in the null space of (z − 1)²·M + z·T²·K + (z − 1)·T·Z, by inverse iteration with
/// a pivoting tridiagonal solve (scaled to unit length).
std::vector<std::complex<double>> chain_mode_shape(const LinearSystem& system,
                                                   std::complex<double> z, int passes = 2);

}  // namespace archet
