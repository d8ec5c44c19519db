#pragma once
// Symmetric eigenproblems as Eigen's dense solver solves them, bit for bit, without reducing a
// matrix that is already tridiagonal (a chain's): the string tunings and the stability check
// solve them at each of their corrections, and every shipped string's bytes depend on them.

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "archet/model/linear_system.hpp"

namespace archet {

struct SymmetricEigen {
    Eigen::VectorXd values;   ///< ascending
    Eigen::MatrixXd vectors;  ///< unit columns; empty unless asked for
    bool converged = false;
};

/// The eigenvalues (and, with `options` Eigen::ComputeEigenvectors, the eigenvectors) of a
/// symmetric matrix, of which the lower triangle is read. A tridiagonal one with finite entries
/// goes to the tridiagonal solver as its two diagonals, scaled as the dense solver scales the
/// lower triangle: the dense solver's Householder reflections are then each the identity (the
/// column below the subdiagonal is zero), so the result is its own to the bit
/// (symmetric_eigen_test.cpp holds it to that).
SymmetricEigen symmetric_eigen(const Eigen::SparseMatrix<double>& symmetric, int options);

/// M^(−1/2)·K·M^(−1/2), its entries (m_r^(−1/2)·K_rc)·m_c^(−1/2) as the dense product computes
/// them.
Eigen::SparseMatrix<double> mass_normalised_stiffness(const LinearSystem& system);

/// The system's undamped modes: M^(−1/2)·K·M^(−1/2)·y = λ·y (their shapes are φ = M^(−1/2)·y).
SymmetricEigen undamped_eigen(const LinearSystem& system, int options);

}  // namespace archet
