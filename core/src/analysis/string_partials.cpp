#include "archet/analysis/string_partials.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/mode_shape.hpp"

namespace archet {

namespace {

using Complex = std::complex<double>;

double entry(const Eigen::SparseMatrix<double>& m, int row, int column) {
    return m.coeff(row, column);
}

// Solves the tridiagonal system (sub, diagonal, super) · x = b by Gaussian elimination with
// row interchanges (LAPACK's gtsv): stable whatever the pivots. A pivot that is exactly zero,
// the singular matrix inverse iteration aims at, is taken as the smallest normal number.
std::vector<Complex> solve_tridiagonal(std::vector<Complex> sub, std::vector<Complex> diagonal,
                                       std::vector<Complex> super, std::vector<Complex> b) {
    const int n = static_cast<int>(diagonal.size());
    std::vector<Complex> second(n, 0.0);  // fill-in two places right of the diagonal
    for (int i = 0; i + 1 < n; ++i) {
        if (std::abs(sub[i]) > std::abs(diagonal[i])) {  // row i + 1 pivots: swap the rows
            std::swap(diagonal[i], sub[i]);
            std::swap(super[i], diagonal[i + 1]);
            if (i + 2 < n) std::swap(second[i], super[i + 1]);
            std::swap(b[i], b[i + 1]);
        }
        if (diagonal[i] == 0.0) diagonal[i] = std::numeric_limits<double>::min();
        const Complex factor = sub[i] / diagonal[i];
        diagonal[i + 1] -= factor * super[i];
        if (i + 2 < n) super[i + 1] -= factor * second[i];
        b[i + 1] -= factor * b[i];
    }
    if (diagonal[n - 1] == 0.0) diagonal[n - 1] = std::numeric_limits<double>::min();
    std::vector<Complex> x(n);
    for (int i = n - 1; i >= 0; --i) {
        Complex v = b[i];
        if (i + 1 < n) v -= super[i] * x[i + 1];
        if (i + 2 < n) v -= second[i] * x[i + 2];
        x[i] = v / diagonal[i];
    }
    return x;
}

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
    const double t = sys.dt;
    // Row i of (z − 1)²·M + z·T²·K + (z − 1)·T·Z.
    auto q = [&](int i, int j) {
        const Complex mass = i == j ? sys.mass[i] : 0.0;
        return (z - 1.0) * (z - 1.0) * mass + z * (t * t) * entry(sys.stiffness, i, j) +
               (z - 1.0) * t * entry(sys.damping, i, j);
    };
    std::vector<Complex> sub(std::max(n - 1, 0)), diagonal(n), super(std::max(n - 1, 0));
    for (int i = 0; i < n; ++i) {
        diagonal[i] = q(i, i);
        if (i + 1 < n) sub[i] = q(i + 1, i), super[i] = q(i, i + 1);
    }
    // The root is exact to rounding, so the matrix is singular to rounding: two solves from an
    // even start leave the null vector alone.
    std::vector<Complex> shape(n, 1.0);
    for (int pass = 0; pass < 2; ++pass) {
        shape = solve_tridiagonal(sub, diagonal, super, shape);
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

}  // namespace

std::vector<double> string_partial_frequencies(const LinearSystem& sys, const Model& model) {
    if (!sys.fingers.empty() || !is_tridiagonal(sys))
        return partials_of_the_whole_analysis(sys, model);
    check_analysable(sys);
    const double dt = sys.dt;
    // Without eigenvectors Eigen runs the same reduction and QR steps on the Schur form and
    // only leaves out accumulating their basis: the roots are analyse_modes()' to the bit. The
    // shapes come from another solve, so a mode whose energy is split within rounding of half
    // and half could be classed otherwise; no string has one.
    const Eigen::EigenSolver<Eigen::MatrixXd> solver(update_matrix(sys), false);
    const std::vector<bool> is_support = support_dofs(sys, model);
    std::vector<std::pair<double, bool>> modes;  // frequency, support
    for (const Complex& root : solver.eigenvalues()) {
        if (root.imag() <= 0.0) continue;  // as analyse_modes(): one of each pair, no real roots
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
