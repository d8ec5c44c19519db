#pragma once
// The explicit scheme's stability bound. Per mode with normalised stiffness K and damping Z
// the scheme is stable when K + 2Z < 4 (physics.md §1); over a whole model that is the
// largest eigenvalue of M^-½ (K·T² + 2·Z·T) M^-½, which must stay below 4.

#include <string>
#include <vector>

#include "archet/model/linear_system.hpp"

namespace archet {

struct StabilityReport {
    std::string rate;
    double dt = 0.0;
    double largest_eigenvalue = 0.0;  ///< of the normalised matrix; stable below 4
    std::string stiffest_dof;         ///< MAT with the largest normalised row sum
    double stiffest_row_sum = 0.0;
    bool stable() const { return largest_eigenvalue < kLimit; }
    /// Fraction of the bound left: 1 − λ/4 (negative when unstable).
    double margin() const { return 1.0 - largest_eigenvalue / kLimit; }
    static constexpr double kLimit = 4.0;
};

/// With `exact` false, a Gershgorin row-sum bound that already proves stability is reported
/// instead of the eigenvalue (cheap for huge models); the eigenvalue is computed otherwise.
StabilityReport analyse_stability(const LinearSystem& system, bool exact = true);

/// One report per rate level of the model.
std::vector<StabilityReport> analyse_stability(const Model& model, bool exact = true);

/// Largest eigenvalue of a symmetric sparse matrix (dense below a few hundred rows, else
/// Lanczos with full re-orthogonalisation plus its residual bound, an upper estimate).
double largest_eigenvalue(const Eigen::SparseMatrix<double>& symmetric);

}  // namespace archet
