#include "archet/model/symmetric_eigen.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace archet {

namespace {

SymmetricEigen result(const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& solver, int options,
                      double scale) {
    SymmetricEigen out;
    out.converged = solver.info() == Eigen::Success;
    if (!out.converged) return out;
    out.values = solver.eigenvalues() * scale;
    if (options & Eigen::ComputeEigenvectors) out.vectors = solver.eigenvectors();
    return out;
}

// Tridiagonal with finite entries: a NaN or an infinity the dense solver spreads through its
// reduction (and reports as no convergence), where the tridiagonal solver may leave it in a
// block of its own.
bool is_finite_tridiagonal(const Eigen::SparseMatrix<double>& a) {
    for (int column = 0; column < a.outerSize(); ++column)
        for (Eigen::SparseMatrix<double>::InnerIterator it(a, column); it; ++it)
            if (!std::isfinite(it.value()) ||
                (it.value() != 0.0 && std::abs(it.row() - it.col()) > 1))
                return false;
    return true;
}

}  // namespace

SymmetricEigen symmetric_eigen(const Eigen::SparseMatrix<double>& a, int options) {
    const int n = static_cast<int>(a.rows());
    if (n == 0) return {{}, {}, true};  // (the dense solver reads the largest entry)
    if (n < 2 || !is_finite_tridiagonal(a))
        return result(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(a), options),
                      options, 1.0);
    // The dense solver divides its lower triangle by the largest magnitude in it (the upper one
    // may differ in its last bits, and is never read) before reducing it, and multiplies λ after.
    Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(n), sub = Eigen::VectorXd::Zero(n - 1);
    double largest = 0;
    for (int column = 0; column < a.outerSize(); ++column)
        for (Eigen::SparseMatrix<double>::InnerIterator it(a, column); it; ++it) {
            if (it.row() >= it.col()) largest = std::max(largest, std::abs(it.value()));
            if (it.row() == it.col()) diagonal[it.col()] = it.value();
            if (it.row() == it.col() + 1) sub[it.col()] = it.value();
        }
    if (largest == 0) largest = 1;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
    solver.computeFromTridiagonal(diagonal / largest, sub / largest, options);
    return result(solver, options, largest);
}

Eigen::SparseMatrix<double> mass_normalised_stiffness(const LinearSystem& sys) {
    const int n = sys.size();
    const Eigen::VectorXd scale = sys.mass.cwiseSqrt().cwiseInverse();
    std::vector<Eigen::Triplet<double>> entries;
    for (int column = 0; column < sys.stiffness.outerSize(); ++column)
        for (Eigen::SparseMatrix<double>::InnerIterator it(sys.stiffness, column); it; ++it)
            entries.emplace_back(it.row(), it.col(),
                                 (scale[it.row()] * it.value()) * scale[it.col()]);
    Eigen::SparseMatrix<double> normalised(n, n);
    normalised.setFromTriplets(entries.begin(), entries.end());
    return normalised;
}

SymmetricEigen undamped_eigen(const LinearSystem& sys, int options) {
    return symmetric_eigen(mass_normalised_stiffness(sys), options);
}

}  // namespace archet
