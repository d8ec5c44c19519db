#include "archet/analysis/mode_shape.hpp"

#include <Eigen/SparseLU>
#include <cmath>

#include "archet/analysis/string_partials.hpp"

namespace archet {

namespace {

using Complex = std::complex<double>;
using SparseComplex = Eigen::SparseMatrix<Complex>;

std::optional<std::vector<Complex>> sparse_mode_shape(const LinearSystem& sys, Complex z,
                                                      int passes) {
    const int n = sys.size();
    Eigen::SparseLU<SparseComplex> lu;
    lu.compute(quadratic_pencil(sys, z));
    if (lu.info() != Eigen::Success) return std::nullopt;
    // The root is exact to rounding, so the matrix is singular to rounding: a few solves from an
    // even start (two, unless a close root asks for more) leave the null vector alone (as
    // chain_mode_shape()).
    Eigen::VectorXcd shape = Eigen::VectorXcd::Ones(n);
    for (int pass = 0; pass < passes; ++pass) {
        shape = lu.solve(shape);
        const double largest = shape.cwiseAbs().maxCoeff();  // the solve can near overflow
        if (!(largest > 0) || !std::isfinite(largest)) return std::nullopt;
        shape /= largest;
    }
    return std::vector<Complex>(shape.data(), shape.data() + n);
}

}  // namespace

SparseComplex quadratic_pencil(const LinearSystem& sys, Complex z) {
    const double t = sys.dt;
    SparseComplex p = (z * (t * t)) * sys.stiffness.cast<Complex>() +
                      ((z - 1.0) * t) * sys.damping.cast<Complex>();
    for (int i = 0; i < sys.size(); ++i) p.coeffRef(i, i) += (z - 1.0) * (z - 1.0) * sys.mass[i];
    p.makeCompressed();
    return p;
}

std::optional<std::vector<Complex>> mode_shape(const LinearSystem& sys, Complex z, int passes) {
    if (sys.size() == 0) return std::nullopt;
    if (is_tridiagonal(sys)) return chain_mode_shape(sys, z, passes);
    return sparse_mode_shape(sys, z, passes);
}

bool EnergySplit::finite() const {
    return kinetic > 0 && std::isfinite(kinetic) && std::isfinite(in_supports);
}

EnergySplit energy_split(const LinearSystem& sys, const std::vector<bool>& is_support,
                         const std::vector<Complex>& shape) {
    EnergySplit split;
    for (int i = 0; i < sys.size(); ++i) {
        const double e = sys.mass[i] * std::norm(shape[i]);
        split.kinetic += e;
        if (is_support[i]) split.in_supports += e;
    }
    return split;
}

}  // namespace archet
