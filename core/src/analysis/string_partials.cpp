#include "archet/analysis/string_partials.hpp"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <utility>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/mode_shape.hpp"
#include "archet/analysis/update_root_near.hpp"
#include "chain_pencil.hpp"

namespace archet {

namespace {

using Complex = std::complex<double>;

// To unit length, scaled by the largest entry first: the solve's result can be near overflow.
void normalise(std::vector<Complex>& v) {
    double largest = 0;
    for (const Complex& c : v) largest = std::max(largest, std::abs(c));
    for (Complex& c : v) c /= largest;
    double norm = 0;
    for (const Complex& c : v) norm += std::norm(c);
    norm = std::sqrt(norm);
    for (Complex& c : v) c /= norm;
}

}  // namespace

bool is_tridiagonal(const LinearSystem& sys) {
    for (const Eigen::SparseMatrix<double>* m : {&sys.stiffness, &sys.damping})
        for (int column = 0; column < m->outerSize(); ++column)
            for (Eigen::SparseMatrix<double>::InnerIterator it(*m, column); it; ++it)
                if (it.value() != 0.0 && std::abs(it.row() - it.col()) > 1) return false;
    return true;
}

std::vector<Complex> chain_mode_shape(const LinearSystem& sys, Complex z) {
    const int n = sys.size();
    if (n == 0) return {};
    const ChainPencil pencil(sys);
    // The root is exact to rounding, so the matrix is singular to rounding: two solves from an
    // even start leave the null vector alone.
    std::vector<Complex> shape(n, 1.0);
    for (int pass = 0; pass < 2; ++pass) {
        shape = pencil.solve(z, shape);
        normalise(shape);
    }
    return shape;
}

namespace {

std::vector<double> partials_of_the_whole_analysis(const LinearSystem& sys, const Model& model) {
    std::vector<double> partials;
    for (const ModeInfo& mode : analyse_modes(sys, model).modes)
        if (!mode.support) partials.push_back(mode.frequency);
    return partials;
}

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
    for (int k = 0; k < n; ++k) {
        double nearest = std::numeric_limits<double>::infinity();
        for (int j = 0; j < n; ++j)
            if (j != k) nearest = std::min(nearest, std::abs(guesses[j] - guesses[k]));
        if (!(std::abs(roots[k] - guesses[k]) < 0.5 * nearest)) return std::nullopt;
    }
    return roots;
}

std::vector<double> string_partial_frequencies(const LinearSystem& sys, const Model& model) {
    if (!sys.fingers.empty() || !is_tridiagonal(sys))
        return partials_of_the_whole_analysis(sys, model);
    check_analysable(sys);
    const double dt = sys.dt;
    std::optional<std::vector<Complex>> roots = chain_update_roots(sys);
    if (!roots) {
        // The dense solve of every root, as analyse_modes() makes it (without eigenvectors
        // Eigen runs the same reduction and QR steps and only leaves out their basis).
        const Eigen::EigenSolver<Eigen::MatrixXd> solver(update_matrix(sys), false);
        roots.emplace();
        for (const Complex& root : solver.eigenvalues())
            if (root.imag() > 0.0) roots->push_back(root);  // one of each pair, no real roots
    }
    // The shapes come from a solve of their own, so a mode whose energy is split within
    // rounding of half and half could be classed otherwise than analyse_modes() classes it; no
    // string has one.
    const std::vector<bool> is_support = support_dofs(sys, model);
    std::vector<std::pair<double, bool>> modes;  // frequency, support
    for (const Complex& root : *roots) {
        const EnergySplit energy = energy_split(sys, is_support, chain_mode_shape(sys, root));
        if (!energy.finite())  // a shape lost to overflow
            return partials_of_the_whole_analysis(sys, model);
        modes.emplace_back(root_frequency(root, dt), energy.support());
    }
    std::sort(modes.begin(), modes.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<double> partials;
    for (const auto& [frequency, support] : modes)
        if (!support) partials.push_back(frequency);
    return partials;
}

}  // namespace archet
