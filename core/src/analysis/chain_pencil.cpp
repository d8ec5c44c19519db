#include "chain_pencil.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace archet {

ChainPencil::ChainPencil(const LinearSystem& sys)
    : mass_(sys.mass.data(), sys.mass.data() + sys.size()),
      k_diagonal_(sys.size()),
      k_off_(std::max(sys.size() - 1, 0)),
      z_diagonal_(sys.size()),
      z_off_(std::max(sys.size() - 1, 0)),
      dt_(sys.dt) {
    for (int i = 0; i < sys.size(); ++i) {
        k_diagonal_[i] = sys.stiffness.coeff(i, i), z_diagonal_[i] = sys.damping.coeff(i, i);
        if (i + 1 < sys.size())
            k_off_[i] = sys.stiffness.coeff(i + 1, i), z_off_[i] = sys.damping.coeff(i + 1, i);
    }
    for (const std::vector<double>* v : {&mass_, &k_diagonal_, &k_off_, &z_diagonal_, &z_off_})
        for (double c : *v) finite_ = finite_ && std::isfinite(c);
    finite_ = finite_ && std::isfinite(dt_);
}

std::vector<ChainPencil::Complex> ChainPencil::solve(Complex z, std::vector<Complex> b) const {
    const int n = size();
    if (n == 0) return b;
    const double t = dt_;
    const Complex mass_factor = (z - 1.0) * (z - 1.0), stiffness_factor = z * (t * t),
                  damping_factor = (z - 1.0) * t;
    // Row i of P(z): the sub-diagonal (i + 1, i) equals the super-diagonal (i, i + 1).
    std::vector<Complex> diagonal(n), sub(std::max(n - 1, 0)), super(std::max(n - 1, 0));
    for (int i = 0; i < n; ++i) {
        diagonal[i] = mass_factor * mass_[i] + stiffness_factor * k_diagonal_[i] +
                      damping_factor * z_diagonal_[i];
        if (i + 1 < n)
            sub[i] = super[i] = stiffness_factor * k_off_[i] + damping_factor * z_off_[i];
    }
    // Gaussian elimination with row interchanges (LAPACK's gtsv): stable whatever the pivots. A
    // pivot that is exactly zero, the singular matrix inverse iteration aims at, is taken as the
    // smallest normal number.
    std::vector<Complex> second(n, Complex{});  // fill-in two places right of the diagonal
    for (int i = 0; i + 1 < n; ++i) {
        if (std::abs(sub[i]) > std::abs(diagonal[i])) {  // row i + 1 pivots: swap the rows
            std::swap(diagonal[i], sub[i]);
            std::swap(super[i], diagonal[i + 1]);
            if (i + 2 < n) std::swap(second[i], super[i + 1]);
            std::swap(b[i], b[i + 1]);
        }
        if (diagonal[i] == Complex{}) diagonal[i] = std::numeric_limits<double>::min();
        const Complex factor = sub[i] / diagonal[i];
        diagonal[i + 1] -= factor * super[i];
        if (i + 2 < n) super[i + 1] -= factor * second[i];
        b[i + 1] -= factor * b[i];
    }
    if (diagonal[n - 1] == Complex{}) diagonal[n - 1] = std::numeric_limits<double>::min();
    std::vector<Complex> x(n);
    for (int i = n - 1; i >= 0; --i) {
        Complex v = b[i];
        if (i + 1 < n) v -= super[i] * x[i + 1];
        if (i + 2 < n) v -= second[i] * x[i + 2];
        x[i] = v / diagonal[i];
    }
    return x;
}

}  // namespace archet
