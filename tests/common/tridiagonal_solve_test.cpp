// The tridiagonal solve against a dense LU: real and complex, with pivots that need the rows
// swapped, and on the exactly singular matrix inverse iteration aims at.

#include "archet/common/tridiagonal_solve.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

namespace archet {
namespace {

template <class T>
using Dense = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
template <class T>
using Column = Eigen::Matrix<T, Eigen::Dynamic, 1>;

template <class T>
Dense<T> dense_of(const std::vector<T>& diagonal, const std::vector<T>& sub,
                  const std::vector<T>& super) {
    const int n = static_cast<int>(diagonal.size());
    Dense<T> a = Dense<T>::Zero(n, n);
    for (int i = 0; i < n; ++i) {
        a(i, i) = diagonal[i];
        if (i + 1 < n) a(i + 1, i) = sub[i], a(i, i + 1) = super[i];
    }
    return a;
}

// A matrix whose diagonal is small against its neighbours at every other row: elimination
// without swapping rows would divide by those small pivots.
template <class T>
void expect_the_dense_solve(T unit) {
    const int n = 41;
    std::vector<T> diagonal(n), sub(n - 1), super(n - 1), b(n);
    for (int i = 0; i < n; ++i) {
        diagonal[i] = unit * (i % 2 == 0 ? 1e-9 * (1 + i) : 3.0 + std::sin(i));
        b[i] = unit * std::cos(0.3 * i) + T(0.1 * i);
        if (i + 1 < n) sub[i] = unit * (2.0 + std::cos(i)), super[i] = T(-1.5 + 0.01 * i);
    }
    const Dense<T> a = dense_of(diagonal, sub, super);
    const Column<T> rhs = Eigen::Map<const Column<T>>(b.data(), n);
    const Column<T> expected = a.partialPivLu().solve(rhs);
    const std::vector<T> x = tridiagonal_solve(diagonal, sub, super, b);
    const Column<T> solved = Eigen::Map<const Column<T>>(x.data(), n);
    EXPECT_LE((solved - expected).norm(), 1e-12 * expected.norm());
    EXPECT_LE((a * solved - rhs).norm(), 1e-13 * (a.norm() * solved.norm()));
}

TEST(TridiagonalSolve, IsTheDenseSolveWithRowsSwapped) {
    expect_the_dense_solve<double>(1.0);
    expect_the_dense_solve<std::complex<double>>({0.6, -0.8});
}

// [1 1; 1 1] is singular: the zero pivot is taken as the smallest normal number, and the
// solution, finite, points along the null vector (1, −1), as one step of inverse iteration does.
TEST(TridiagonalSolve, StaysFiniteOnASingularMatrix) {
    const std::vector<double> x = tridiagonal_solve<double>({1.0, 1.0}, {1.0}, {1.0}, {1.0, 0.0});
    ASSERT_EQ(x.size(), 2u);
    EXPECT_TRUE(std::isfinite(x[0]) && std::isfinite(x[1]));
    EXPECT_GT(std::abs(x[0]), 1e300);
    EXPECT_DOUBLE_EQ(x[0], -x[1]);
}

TEST(TridiagonalSolve, SolvesOneRowAndNone) {
    EXPECT_EQ(tridiagonal_solve<double>({4.0}, {}, {}, {2.0}), std::vector<double>{0.5});
    EXPECT_TRUE(tridiagonal_solve<double>({}, {}, {}, {}).empty());
}

}  // namespace
}  // namespace archet
