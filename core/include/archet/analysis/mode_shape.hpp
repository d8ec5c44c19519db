#pragma once
// A mode's shape found from its root alone, without the dense eigenbasis, and how its kinetic
// energy splits between the string and its supports: what tells a string's partial from a
// bridge's mode wherever only a few modes are asked (string_partials.hpp,
// string_first_mode.hpp).

#include <complex>
#include <optional>
#include <vector>

#include "archet/model/linear_system.hpp"

namespace archet {

/// (z − 1)²·M + z·T²·K + (z − 1)·T·Z: the matrix whose null vectors are the shapes of the
/// scheme's modes with root z (update_matrix() without fingers, multiplied out), complex
/// symmetric as K and Z are. Its pattern is the same for every z.
Eigen::SparseMatrix<std::complex<double>> quadratic_pencil(const LinearSystem& system,
                                                           std::complex<double> z);

/// The shape of the scheme's mode with root z on a system without fingers: a null vector of
/// (z − 1)²·M + z·T²·K + (z − 1)·T·Z by inverse iteration, with the pivoting tridiagonal solve
/// on a chain (chain_mode_shape()) and a sparse LU where links join more than neighbours (a
/// body's bridge point). Nothing when the LU finds the matrix singular to the last bit or the
/// solve overflows. Two passes of the iteration unless asked for more (a root close to another,
/// whose shape each pass separates from the other's by the ratio of their distances to z).
std::optional<std::vector<std::complex<double>>> mode_shape(const LinearSystem& system,
                                                            std::complex<double> z, int passes = 2);

/// A shape's kinetic energy Σ m·|v|², and the part of it in the DOFs `is_support` marks.
struct EnergySplit {
    double kinetic = 0, in_supports = 0;
    /// Whether the sums are finite with some energy to split.
    bool finite() const;
    /// analyse_modes()' test: more than half in the supports.
    bool support() const { return in_supports > 0.5 * kinetic; }
};
EnergySplit energy_split(const LinearSystem& system, const std::vector<bool>& is_support,
                         const std::vector<std::complex<double>>& shape);

}  // namespace archet
