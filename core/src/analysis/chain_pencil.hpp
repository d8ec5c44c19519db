#pragma once
// The quadratic pencil P(z) = (z − 1)²·M + z·T²·K + (z − 1)·T·Z of a chain (a system whose
// links join neighbours alone: tridiagonal K and Z), held as its diagonals, and the solve of
// P(z)·x = b in O(n): what inverse iteration on a chain's modes needs, in microseconds where a
// sparse LU takes a millisecond. Private to the analysis sources.

#include <complex>
#include <vector>

#include "archet/model/linear_system.hpp"

namespace archet {

class ChainPencil {
  public:
    using Complex = std::complex<double>;

    /// The diagonals of a system that is_tridiagonal() accepts.
    explicit ChainPencil(const LinearSystem& system);

    int size() const { return static_cast<int>(mass_.size()); }
    /// Whether its coefficients are all finite (a solve that overflows is then one at a root).
    bool finite() const { return finite_; }
    /// x with P(z)·x = b, by Gaussian elimination with row interchanges (LAPACK's gtsv); an
    /// exactly zero pivot is taken as the smallest normal number.
    std::vector<Complex> solve(Complex z, std::vector<Complex> b) const;

  private:
    std::vector<double> mass_, k_diagonal_, k_off_, z_diagonal_, z_off_;  ///< off: (i + 1, i)
    double dt_;
    bool finite_ = true;
};

}  // namespace archet
