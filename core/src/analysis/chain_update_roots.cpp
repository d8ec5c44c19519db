#include "archet/analysis/chain_update_roots.hpp"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "archet/analysis/update_root_near.hpp"

namespace archet {

namespace {

using Complex = std::complex<double>;

// φᵀ·A·φ.
double quadratic_form(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& phi) {
    return phi.dot(a * phi);
}

}  // namespace

std::optional<std::vector<Complex>> chain_update_roots(const LinearSystem& sys) {
    if (sys.size() == 0 || !sys.fingers.empty() || !is_tridiagonal(sys)) return std::nullopt;
    const int n = sys.size();
    const double t = sys.dt;
    // K·φ = λ·M·φ, made symmetric by M^(−1/2) on both sides: still tridiagonal.
    const Eigen::VectorXd scale = sys.mass.cwiseSqrt().cwiseInverse();
    Eigen::VectorXd diagonal(n), sub(n - 1);
    for (int i = 0; i < n; ++i) {
        diagonal[i] = sys.stiffness.coeff(i, i) * scale[i] * scale[i];
        if (i + 1 < n) sub[i] = sys.stiffness.coeff(i + 1, i) * scale[i] * scale[i + 1];
    }
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> undamped;
    undamped.computeFromTridiagonal(diagonal, sub, Eigen::ComputeEigenvectors);
    if (undamped.info() != Eigen::Success) return std::nullopt;
    std::vector<Complex> guesses(n), roots(n);
    for (int k = 0; k < n; ++k) {
        const Eigen::VectorXd phi = scale.cwiseProduct(undamped.eigenvectors().col(k));
        // m·w² + (T²·k + T·c)·w + T²·k = 0 for z = 1 + w (rayleigh_root() in update_root_near).
        const double m = phi.dot(sys.mass.cwiseProduct(phi));
        const double kt2 = t * t * quadratic_form(sys.stiffness, phi);
        const double b = kt2 + t * quadratic_form(sys.damping, phi);
        const double discriminant = 4.0 * m * kt2 - b * b;
        if (!(m > 0) || !(discriminant > 0)) return std::nullopt;  // no oscillating pair
        guesses[k] = {1.0 - b / (2.0 * m), std::sqrt(discriminant) / (2.0 * m)};
        const std::optional<Complex> root =
            update_root_near(sys, guesses[k], std::span<const double>(phi.data(), n));
        if (!root || !(root->imag() > 0.0)) return std::nullopt;
        roots[k] = *root;
    }
    // Two roots that each lie nearer their own guess than half way to the other's are apart; the
    // margin takes in how far update_root_near() stops from a root (1e-12 of z − 1 at most), so
    // that two estimates of one root are not taken for two.
    for (int k = 0; k < n; ++k) {
        double nearest = std::numeric_limits<double>::infinity();
        for (int j = 0; j < n; ++j)
            if (j != k) nearest = std::min(nearest, std::abs(guesses[j] - guesses[k]));
        const double margin = 1e-10 * std::abs(roots[k] - 1.0) + 1e-14;
        if (!(std::abs(roots[k] - guesses[k]) < 0.5 * nearest - margin)) return std::nullopt;
    }
    return roots;
}

}  // namespace archet
