#include "archet/analysis/update_root_near.hpp"

#include <Eigen/SparseLU>
#include <cmath>
#include <limits>
#include <optional>

#include "archet/analysis/mode_shape.hpp"
#include "chain_pencil.hpp"

namespace archet {

namespace {

using Complex = std::complex<double>;
using SparseComplex = Eigen::SparseMatrix<Complex>;

// P'(z)·x = (2(z − 1)·M + T²·K + T·Z)·x.
Eigen::VectorXcd derivative_times(const LinearSystem& sys, Complex z, const Eigen::VectorXcd& x) {
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

// The root of xᵀ·P(z)·x = 0 nearest `near`. With z = 1 + w and m = xᵀMx, kt2 = T²·xᵀKx and
// zt = T·xᵀZx, it is m·w² + (kt2 + zt)·w + kt2 = 0, solved for w: a low mode's roots lie near
// 1, where z itself would cancel digits.
Complex rayleigh_root(const LinearSystem& sys, const Eigen::VectorXcd& x, Complex near) {
    const Complex m = x.cwiseProduct(sys.mass.cast<Complex>().cwiseProduct(x)).sum();
    const Complex kt2 = (sys.dt * sys.dt) * bilinear(sys.stiffness, x);
    const Complex zt = sys.dt * bilinear(sys.damping, x);
    const Complex b = kt2 + zt;
    const Complex root = std::sqrt(b * b - 4.0 * m * kt2);
    // The larger w without cancellation, the other from their product kt2/m.
    const Complex large = -(b + (std::real(std::conj(b) * root) >= 0 ? root : -root)) / (2.0 * m);
    const Complex small = large != 0.0 ? kt2 / (m * large) : Complex{};
    const Complex z1 = 1.0 + large, z2 = 1.0 + small;
    return std::abs(z1 - near) <= std::abs(z2 - near) ? z1 : z2;
}

// P(shift)⁻¹·b: on a chain by its O(n) solve, else by the sparse LU (its pattern, which
// quadratic_pencil() makes the same at every shift, analysed once).
class PencilSolver {
  public:
    enum class Outcome { Solved, Singular, Failed };

    explicit PencilSolver(const LinearSystem& sys) : sys_(sys) {
        if (is_tridiagonal(sys))
            chain_.emplace(sys);
        else
            lu_.analyzePattern(quadratic_pencil(sys, 1.0));
    }
    /// Singular: P(shift) is singular to the last bit (the LU finds a zero pivot; the chain's
    /// solve, which takes one as the smallest normal number, overflows on finite coefficients).
    /// Failed: what is not finite (a coefficient, the shift) made the result so.
    Outcome solve(Complex shift, const Eigen::VectorXcd& b, Eigen::VectorXcd& x) {
        if (chain_) {
            const std::vector<Complex> y =
                chain_->solve(shift, std::vector<Complex>(b.data(), b.data() + b.size()));
            x = Eigen::Map<const Eigen::VectorXcd>(y.data(), b.size());
            if (x.allFinite()) return Outcome::Solved;
            const bool finite_input = chain_->finite() && std::isfinite(shift.real()) &&
                                      std::isfinite(shift.imag()) && b.allFinite();
            return finite_input ? Outcome::Singular : Outcome::Failed;
        }
        lu_.factorize(quadratic_pencil(sys_, shift));
        if (lu_.info() != Eigen::Success) return Outcome::Singular;
        x = lu_.solve(b);
        return Outcome::Solved;
    }

  private:
    const LinearSystem& sys_;
    std::optional<ChainPencil> chain_;
    Eigen::SparseLU<SparseComplex> lu_;
};

}  // namespace

std::optional<Complex> update_root_near(const LinearSystem& sys, Complex guess,
                                        std::span<const double> start) {
    const int n = sys.size();
    if (n == 0 || !sys.fingers.empty()) return std::nullopt;
    // Without a start, a ramp: a string's even modes are odd about its middle, which an even
    // start (all ones) would leave out.
    Eigen::VectorXcd x(n);
    for (int i = 0; i < n; ++i)
        x[i] = start.size() == static_cast<std::size_t>(n) ? start[i]
                                                           : 1.0 + static_cast<double>(i) / n;
    // Steps from the guess itself settle on the root nearest it (each shrinks the others' share
    // by about their distance ratio); once the estimate holds still, the shift follows it and
    // the estimate converges fast, until rounding stops it: it is taken when it moves by a few
    // roundings, or stops moving less while already within 1e-12 of w = z − 1 (a part in 10¹²
    // of the frequency).
    constexpr int kMostSteps = 24;
    constexpr double kShiftFollowsBelow = 1e-9,
                     kFewRoundings = 4.0 * std::numeric_limits<double>::epsilon(),
                     kNearlySettled = 1e-12;
    PencilSolver pencil(sys);
    Complex z = guess, shift = guess;
    bool following = false;
    double last_move = std::numeric_limits<double>::infinity();
    for (int step = 0; step < kMostSteps; ++step) {
        if (following) shift = z;
        Eigen::VectorXcd solved;
        const PencilSolver::Outcome outcome =
            pencil.solve(shift, derivative_times(sys, shift, x), solved);
        // Singular to the last bit: the shift is a root (the guess itself, when not following).
        if (outcome == PencilSolver::Outcome::Singular) return following ? z : guess;
        if (outcome == PencilSolver::Outcome::Failed) return std::nullopt;
        x = std::move(solved);
        const double largest = x.cwiseAbs().maxCoeff();  // the solve can near overflow
        if (!(largest > 0) || !std::isfinite(largest)) return std::nullopt;
        x /= largest;
        const Complex next = rayleigh_root(sys, x, following ? z : guess);
        if (!std::isfinite(next.real()) || !std::isfinite(next.imag())) return std::nullopt;
        const double move = std::abs(next - z);
        z = next;
        if (following && (move <= kFewRoundings * std::abs(z) ||
                          (move >= last_move && move <= kNearlySettled * std::abs(z - 1.0))))
            return z;
        following = following || (step > 0 && move <= kShiftFollowsBelow * std::abs(z));
        last_move = move;
    }
    return std::nullopt;
}

}  // namespace archet
