#include "archet/analysis/update_root_near.hpp"

#include <Eigen/SparseLU>
#include <cmath>
#include <limits>

namespace archet {

namespace {

using Complex = std::complex<double>;
using SparseComplex = Eigen::SparseMatrix<Complex>;

// (z − 1)²·M + z·T²·K + (z − 1)·T·Z, and its derivative in z, 2(z − 1)·M + T²·K + T·Z.
SparseComplex pencil(const LinearSystem& sys, Complex z) {
    const double t = sys.dt;
    SparseComplex p = (z * (t * t)) * sys.stiffness.cast<Complex>() +
                      ((z - 1.0) * t) * sys.damping.cast<Complex>();
    for (int i = 0; i < sys.size(); ++i) p.coeffRef(i, i) += (z - 1.0) * (z - 1.0) * sys.mass[i];
    p.makeCompressed();
    return p;
}

Eigen::VectorXcd slope_times(const LinearSystem& sys, Complex z, const Eigen::VectorXcd& x) {
    const double t = sys.dt;
    Eigen::VectorXcd y =
        (t * t) * (sys.stiffness.cast<Complex>() * x) + t * (sys.damping.cast<Complex>() * x);
    y += (2.0 * (z - 1.0)) * sys.mass.cast<Complex>().cwiseProduct(x);
    return y;
}

// xᵀA·x without conjugation: P is complex symmetric, so its left null vector is x itself.
Complex bilinear(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXcd& x) {
    return x.cwiseProduct(a.cast<Complex>() * x).sum();
}

// The root of xᵀ·P(z)·x = 0 nearest `near`. With z = 1 + w, m·w² + (T²k + T·d)·w + T²k = 0,
// solved for w: the roots of a low mode lie near 1, where z itself would cancel digits.
Complex rayleigh_root(const LinearSystem& sys, const Eigen::VectorXcd& x, Complex near) {
    const double t = sys.dt;
    const Complex m = x.cwiseProduct(sys.mass.cast<Complex>().cwiseProduct(x)).sum();
    const Complex k = (t * t) * bilinear(sys.stiffness, x);
    const Complex d = t * bilinear(sys.damping, x);
    const Complex b = k + d;
    const Complex root = std::sqrt(b * b - 4.0 * m * k);
    // The larger w without cancellation, the other from the product of the two (k/m).
    const Complex large = -(b + (std::real(std::conj(b) * root) >= 0 ? root : -root)) / (2.0 * m);
    const Complex small = large != 0.0 ? k / (m * large) : Complex{};
    const Complex z1 = 1.0 + large, z2 = 1.0 + small;
    return std::abs(z1 - near) <= std::abs(z2 - near) ? z1 : z2;
}

}  // namespace

std::optional<Complex> update_root_near(const LinearSystem& sys, Complex guess) {
    const int n = sys.size();
    if (n == 0 || !sys.fingers.empty()) return std::nullopt;
    // A ramp to start from: a string's even modes are odd about its middle, which an even
    // start (all ones) would leave out.
    Eigen::VectorXcd x(n);
    for (int i = 0; i < n; ++i) x[i] = 1.0 + static_cast<double>(i) / n;
    // Steps from the guess itself settle on the root nearest it (each multiplies the others'
    // share by their distance ratio); once the estimate holds still, the shift follows it.
    constexpr int kMostSteps = 24;
    constexpr double kSettledGuess = 1e-9,
                     kSettledRoot = 4.0 * std::numeric_limits<double>::epsilon();
    Complex z = guess, shift = guess;
    bool following = false;
    for (int step = 0; step < kMostSteps; ++step) {
        if (following) shift = z;
        Eigen::SparseLU<SparseComplex> lu;
        lu.compute(pencil(sys, shift));
        // Singular to the last bit: the shift is a root.
        if (lu.info() != Eigen::Success) return following ? std::optional(z) : std::nullopt;
        x = lu.solve(slope_times(sys, shift, x));
        const double largest = x.cwiseAbs().maxCoeff();  // the solve can near overflow
        if (!(largest > 0) || !std::isfinite(largest)) return std::nullopt;
        x /= largest;
        const Complex next = rayleigh_root(sys, x, z);
        if (!std::isfinite(next.real()) || !std::isfinite(next.imag())) return std::nullopt;
        const double moved = std::abs(next - z) / std::abs(next);
        z = next;
        if (following && moved <= kSettledRoot) return z;
        following = following || (step > 0 && moved <= kSettledGuess);
    }
    return std::nullopt;
}

}  // namespace archet
