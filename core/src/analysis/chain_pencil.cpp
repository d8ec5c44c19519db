#include "chain_pencil.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "archet/common/tridiagonal_solve.hpp"

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
    return tridiagonal_solve(std::move(diagonal), std::move(sub), std::move(super), std::move(b));
}

}  // namespace archet
