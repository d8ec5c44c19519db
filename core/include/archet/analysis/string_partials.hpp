#pragma once
// The frequencies of a string's partials as analyse_modes() finds them, at a fraction of its
// cost on a chain: each root found from its undamped mode by a few tridiagonal solves, and
// each mode's shape, which tells a partial from a mode of the supports, from a tridiagonal solve
// of its own (what a harmonic string's tuning asks for several times).

#include <complex>
#include <optional>
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

/// The roots of a chain's one-step update with a positive imaginary part, one a mode, each
/// found from its undamped mode: the root of φᵀ·P(z)·φ = 0 with the mode's shape φ is the guess,
/// which update_root_near() refines on the chain in microseconds (the dense solve of all the
/// roots takes seconds on a low string). Nothing unless each root lies nearer its own guess
/// than half way to any other: then they are as many distinct roots as the update has pairs, so
/// all of them. Nothing too where the system is not a chain, has a finger, or a mode does not
/// oscillate. (A string's losses move its top partials by more cents than lie between them; the
/// guess from the shape takes that in.)
std::optional<std::vector<std::complex<double>>> chain_update_roots(const LinearSystem& system);

/// Whether every link of the system joins neighbours in the order of its DOFs.
bool is_tridiagonal(const LinearSystem& system);

/// The shape of the scheme's mode with root z on a tridiagonal system without fingers: a
/// vector in the null space of (z − 1)²·M + z·T²·K + (z − 1)·T·Z, by inverse iteration with
/// a pivoting tridiagonal solve (scaled to unit length).
std::vector<std::complex<double>> chain_mode_shape(const LinearSystem& system,
                                                   std::complex<double> z);

}  // namespace archet
