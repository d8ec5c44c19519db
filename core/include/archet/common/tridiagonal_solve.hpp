#pragma once
// The solve of a tridiagonal system in O(n), for real or complex entries: what inverse
// iteration on a chain's modes needs (the string tunings' undamped shapes, the damped roots'
// refinement), in microseconds where a dense LU of a long string takes milliseconds.

#include <cmath>
#include <complex>
#include <limits>
#include <utility>
#include <vector>

namespace archet {

/// x with A·x = b for A with `diagonal` (n), `sub` (A(i + 1, i)) and `super` (A(i, i + 1)), by
/// Gaussian elimination with row interchanges (LAPACK's gtsv): stable whatever the pivots. A
/// pivot that is exactly zero, the singular matrix inverse iteration aims at, is taken as the
/// smallest normal number.
template <class T>
std::vector<T> tridiagonal_solve(std::vector<T> diagonal, std::vector<T> sub, std::vector<T> super,
                                 std::vector<T> b) {
    using Real = decltype(std::abs(T{}));
    const int n = static_cast<int>(diagonal.size());
    if (n == 0) return b;
    std::vector<T> second(n, T{});  // fill-in two places right of the diagonal
    for (int i = 0; i + 1 < n; ++i) {
        if (std::abs(sub[i]) > std::abs(diagonal[i])) {  // row i + 1 pivots: swap the rows
            std::swap(diagonal[i], sub[i]);
            std::swap(super[i], diagonal[i + 1]);
            if (i + 2 < n) std::swap(second[i], super[i + 1]);
            std::swap(b[i], b[i + 1]);
        }
        if (diagonal[i] == T{}) diagonal[i] = std::numeric_limits<Real>::min();
        const T factor = sub[i] / diagonal[i];
        diagonal[i + 1] -= factor * super[i];
        if (i + 2 < n) super[i + 1] -= factor * second[i];
        b[i + 1] -= factor * b[i];
    }
    if (diagonal[n - 1] == T{}) diagonal[n - 1] = std::numeric_limits<Real>::min();
    std::vector<T> x(n);
    for (int i = n - 1; i >= 0; --i) {
        T v = b[i];
        if (i + 1 < n) v -= super[i] * x[i + 1];
        if (i + 2 < n) v -= second[i] * x[i + 2];
        x[i] = v / diagonal[i];
    }
    return x;
}

}  // namespace archet
