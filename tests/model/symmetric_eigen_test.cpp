// The undamped modes of a chain from its two diagonals are the dense solve's, bit for bit: the
// tunings read them at each correction, and every shipped string's bytes depend on them.

#include "archet/model/symmetric_eigen.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "archet/builders/bowed_string.hpp"
#include "archet/builders/string_chain.hpp"
#include "archet/builders/string_losses.hpp"
#include "archet/model/linear_system.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

// What the dense solve gives: the mass-normalised stiffness as a dense matrix.
Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> dense_solve(const LinearSystem& sys, int options) {
    const Eigen::VectorXd scale = sys.mass.cwiseSqrt().cwiseInverse();
    return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(
        scale.asDiagonal() * Eigen::MatrixXd(sys.stiffness) * scale.asDiagonal(), options);
}

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    return a.rows() == b.rows() && a.cols() == b.cols() &&
           std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

void expect_the_dense_solve(const LinearSystem& sys, const std::string& what) {
    const auto dense = dense_solve(sys, Eigen::ComputeEigenvectors);
    ASSERT_EQ(dense.info(), Eigen::Success) << what;
    const SymmetricEigen with_shapes = undamped_eigen(sys, Eigen::ComputeEigenvectors);
    ASSERT_TRUE(with_shapes.converged) << what;
    EXPECT_TRUE(same_bits(with_shapes.values, dense.eigenvalues())) << what;
    EXPECT_TRUE(same_bits(with_shapes.vectors, dense.eigenvectors())) << what;
    const SymmetricEigen values_only = undamped_eigen(sys, Eigen::EigenvaluesOnly);
    ASSERT_TRUE(values_only.converged) << what;
    EXPECT_TRUE(same_bits(values_only.values, dense.eigenvalues())) << what;
    EXPECT_EQ(values_only.vectors.size(), 0) << what;
}

TEST(SymmetricEigen, IsTheDenseSolveOnTunedStrings) {
    struct Case {
        double pitch;
        Tuning tuning;
        int masses;
    };
    const Case cases[] = {{220, Tuning::Homogeneous, 60},  {220, Tuning::Harmonic, 60},
                          {110, Tuning::Homogeneous, 300}, {65, Tuning::Harmonic, 300},
                          {880, Tuning::Harmonic, 12},     {1318.5, Tuning::Homogeneous, 3}};
    for (const Case& c : cases) {
        BowedStringOptions o;
        o.pitch = c.pitch, o.tuning = c.tuning, o.body = "none";
        Model model = tuned_string(o, c.masses);
        apply_string_losses(model, string_elements(c.masses), {0.6, 1.6e-8});
        const LinearSystem sys = assemble_linear_system(model, "audio");
        ASSERT_TRUE(is_tridiagonal(sys));
        expect_the_dense_solve(
            sys, std::to_string(c.pitch) + " Hz, " + std::to_string(c.masses) + " masses");
    }
}

// A chain of masses of three sizes with springs of three stiffnesses: the two triangles of its
// mass-normalised matrix differ in their last bits; still the dense solve's bits.
TEST(SymmetricEigen, IsTheDenseSolveOnAnUnevenChain) {
    Model model = test::chain(9, 1e-3, 500.0, 0.0);
    for (int i = 1; i <= 9; ++i)
        model.find_mat("m" + std::to_string(i))->mass *= 1.0 + 0.37 * (i % 3);
    for (int i = 0; i <= 9; ++i)
        model.find_lia("l" + std::to_string(i))->stiffness *= 1.0 + 1.9 * (i % 3);
    const LinearSystem sys = assemble_linear_system(model);
    const Eigen::VectorXd scale = sys.mass.cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd a =
        scale.asDiagonal() * Eigen::MatrixXd(sys.stiffness) * scale.asDiagonal();
    Eigen::MatrixXd transposed = a.transpose();
    ASSERT_FALSE(same_bits(a, transposed)) << "the triangles are alike after all";
    expect_the_dense_solve(sys, "uneven chain");
}

// The stability check's matrix, M^(−1/2)·(T²·K + 2T·Z)·M^(−1/2) of a damped string as a sparse
// product: its eigenvalues are the dense solve's.
TEST(SymmetricEigen, IsTheDenseSolveOfTheStabilityMatrix) {
    BowedStringOptions o;
    o.pitch = 110, o.body = "none";
    Model model = tuned_string(o, 200);
    apply_string_losses(model, string_elements(200), {0.6, 1.6e-8});
    const LinearSystem sys = assemble_linear_system(model, "audio");
    const Eigen::VectorXd scale = sys.mass.cwiseSqrt().cwiseInverse();
    Eigen::SparseMatrix<double> a =
        sys.stiffness * (sys.dt * sys.dt) + sys.damping * (2.0 * sys.dt);
    a = scale.asDiagonal() * a * scale.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> dense(Eigen::MatrixXd(a),
                                                               Eigen::EigenvaluesOnly);
    const SymmetricEigen solved = symmetric_eigen(a, Eigen::EigenvaluesOnly);
    ASSERT_TRUE(solved.converged);
    EXPECT_TRUE(same_bits(solved.values, dense.eigenvalues()));
}

// Matrices given whole, each against the dense solver on the same matrix.
void expect_the_dense_solve_of(const Eigen::MatrixXd& whole, const std::string& what) {
    const Eigen::SparseMatrix<double> sparse = whole.sparseView(0.0, 0.0);
    for (int options : {Eigen::ComputeEigenvectors, Eigen::EigenvaluesOnly}) {
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> dense(whole, options);
        const SymmetricEigen solved = symmetric_eigen(sparse, options);
        EXPECT_EQ(solved.converged, dense.info() == Eigen::Success) << what;
        if (!solved.converged) continue;
        EXPECT_TRUE(same_bits(solved.values, dense.eigenvalues())) << what;
        if (options == Eigen::ComputeEigenvectors) {
            EXPECT_TRUE(same_bits(solved.vectors, dense.eigenvectors())) << what;
        }
    }
}

// The dense solver reads the lower triangle and scales by the largest entry in it, even where
// the upper one holds a larger; a negative zero on the diagonal, an infinity or a NaN in a block
// of its own: each as the dense solver has it.
TEST(SymmetricEigen, IsTheDenseSolveOfMatricesGivenWhole) {
    Eigen::MatrixXd larger_above(2, 2);
    larger_above << 0.0, 1.0 + std::ldexp(1.0, -52), 1.0, 0.0;
    expect_the_dense_solve_of(larger_above, "the upper triangle larger");
    Eigen::MatrixXd signed_zero(3, 3);
    signed_zero << -0.0, -2.0, 0.0, -2.0, 5.0, -1.0, 0.0, -1.0, -0.0;
    expect_the_dense_solve_of(signed_zero, "negative zeros on the diagonal");
    for (double bad :
         {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        Eigen::MatrixXd apart = Eigen::MatrixXd::Zero(3, 3);
        apart(0, 0) = 1.0, apart(1, 1) = bad, apart(2, 2) = 1.0;
        expect_the_dense_solve_of(apart, "a block of its own: " + std::to_string(bad));
    }
}

// Not a chain (a string on a body): the dense solve itself.
TEST(SymmetricEigen, SolvesWhatIsNotAChainDensely) {
    BowedStringOptions o;
    o.pitch = 440, o.body = "violin";
    const Model model = tuned_string(o, 40);
    const LinearSystem sys = assemble_linear_system(model, "audio");
    ASSERT_FALSE(is_tridiagonal(sys));
    expect_the_dense_solve(sys, "string on a violin body");
}

// One mass and none: the dense solver's own special cases.
TEST(SymmetricEigen, SolvesOneMassAndNone) {
    expect_the_dense_solve(assemble_linear_system(test::chain(1, 1e-3, 500.0, 0.0)), "one mass");
    const SymmetricEigen none = undamped_eigen(LinearSystem{}, Eigen::EigenvaluesOnly);
    EXPECT_TRUE(none.converged);
    EXPECT_EQ(none.values.size(), 0);
}

}  // namespace
}  // namespace archet
