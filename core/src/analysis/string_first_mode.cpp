#include "archet/analysis/string_first_mode.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/string_partials.hpp"

namespace archet {

namespace {

using Complex = std::complex<double>;
using SparseComplex = Eigen::SparseMatrix<Complex>;

// The shape of the mode with root z on a system without fingers: a vector in the null space
// of (z − 1)²·M + z·T²·K + (z − 1)·T·Z by inverse iteration, with a sparse LU where the
// links do not all join neighbours (a body's bridge point). Nothing when the LU finds the
// matrix singular to the last bit: the caller then asks the whole analysis.
std::optional<std::vector<Complex>> mode_shape(const LinearSystem& sys, Complex z) {
    if (is_tridiagonal(sys)) return chain_mode_shape(sys, z);
    const int n = sys.size();
    const double t = sys.dt;
    SparseComplex q = (z * (t * t)) * sys.stiffness.cast<Complex>() +
                      ((z - 1.0) * t) * sys.damping.cast<Complex>();
    for (int i = 0; i < n; ++i) q.coeffRef(i, i) += (z - 1.0) * (z - 1.0) * sys.mass[i];
    q.makeCompressed();
    Eigen::SparseLU<SparseComplex> lu;
    lu.compute(q);
    if (lu.info() != Eigen::Success) return std::nullopt;
    // The root is exact to rounding, so the matrix is singular to rounding: two solves from an
    // even start leave the null vector alone.
    Eigen::VectorXcd shape = Eigen::VectorXcd::Ones(n);
    for (int pass = 0; pass < 2; ++pass) {
        shape = lu.solve(shape);
        const double largest = shape.cwiseAbs().maxCoeff();  // the solve can near overflow
        if (!(largest > 0) || !std::isfinite(largest)) return std::nullopt;
        shape /= largest;
    }
    return std::vector<Complex>(shape.data(), shape.data() + n);
}

struct Root {
    Complex z;
    double frequency, t60;
};

// Whether most of the mode's kinetic energy is in the supports, as analyse_modes() classes
// it; nothing when its shape could not be found.
std::optional<bool> in_supports(const LinearSystem& sys, const std::vector<bool>& is_support,
                                Complex z) {
    const std::optional<std::vector<Complex>> shape = mode_shape(sys, z);
    if (!shape) return std::nullopt;
    double kinetic = 0, supports = 0;
    for (int i = 0; i < sys.size(); ++i) {
        const double e = sys.mass[i] * std::norm((*shape)[i]);
        kinetic += e;
        if (is_support[i]) supports += e;
    }
    if (!(kinetic > 0) || !std::isfinite(kinetic)) return std::nullopt;
    return supports > 0.5 * kinetic;
}

}  // namespace

StringFirstMode string_first_mode(const Model& model) {
    return string_first_mode(sounding_part(model), model);
}

StringFirstMode string_first_mode(const LinearSystem& sys, const Model& model) {
    if (!sys.fingers.empty()) return string_first_mode(analyse_modes(sys, model));
    check_analysable(sys);
    const double dt = sys.dt;
    // Without eigenvectors Eigen runs the same reduction and QR steps on the Schur form and
    // only leaves out accumulating their basis: the roots are analyse_modes()' to the bit.
    const Eigen::EigenSolver<Eigen::MatrixXd> solver(update_matrix(sys), false);
    std::vector<Root> roots;
    for (const Complex& z : solver.eigenvalues()) {
        if (z.imag() <= 0.0) continue;  // as analyse_modes(): one of each pair, no real roots
        const double radius = std::abs(z);
        roots.push_back({z, std::arg(z) / (2.0 * std::numbers::pi * dt),
                         radius < 1.0 ? std::log(1e-3) / std::log(radius) * dt
                                      : std::numeric_limits<double>::infinity()});
    }
    // The same keys in the same order through the same sort: the same order of modes.
    std::sort(roots.begin(), roots.end(),
              [](const auto& a, const auto& b) { return a.frequency < b.frequency; });
    const std::vector<bool> is_support = support_dofs(sys, model);
    for (const Root& root : roots) {
        const std::optional<bool> support = in_supports(sys, is_support, root.z);
        if (!support) return string_first_mode(analyse_modes(sys, model));
        if (!*support) return {root.frequency, root.t60};
    }
    return {};
}

StringFirstMode string_first_mode(const ModalAnalysis& modes) {
    StringFirstMode first;
    for (const ModeInfo& mode : modes.modes)
        if (mode.partial == 1) first = {modes.fundamental, mode.t60};
    return first;
}

}  // namespace archet
