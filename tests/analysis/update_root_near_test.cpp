// One root of the scheme's update found near a guess (what a string's tuning looks at) against
// the dense solve of all of them: the same root, no less exact.

#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/mode_shape.hpp"
#include "archet/analysis/update_root_near.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/linear_system.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

using Complex = std::complex<double>;

Complex on_the_circle(double frequency, double dt) {
    return std::polar(1.0, 2.0 * std::numbers::pi * frequency * dt);
}

Complex nearest(const UpdateRoots& all, Complex to) {
    Complex best{std::numeric_limits<double>::infinity()};
    for (const Complex& z : all.roots)
        if (std::abs(z - to) < std::abs(best - to)) best = z;
    return best;
}

// How far z is from a root: the smallest |P(z)·x| over unit shapes x (inverse iteration), in
// units of the largest mass.
double residual(const LinearSystem& system, Complex z) {
    const Eigen::SparseMatrix<Complex> p = quadratic_pencil(system, z);
    const Eigen::SparseLU<Eigen::SparseMatrix<Complex>> lu(p);
    Eigen::VectorXcd x = Eigen::VectorXcd::LinSpaced(system.size(), 1.0, 2.0);
    for (int pass = 0; pass < 4; ++pass) x = lu.solve(x).normalized();
    return (p * x).norm() / system.mass.maxCoeff();
}

// The dense solve's roots carry an error of a few hundred roundings of |U| ≈ 4, so their
// frequencies (arg(z)·fs/2π) one of about 1e-13 over the angle θ = 2πf·T, relative: the root
// found near the guess is the dense solve's nearest the guess, its frequency agrees to that,
// and it is as near a root (within a factor 2 for rounding).
void expect_the_dense_root(const LinearSystem& system, const UpdateRoots& all, double frequency,
                           const std::string& what) {
    const auto z = update_root_near(system, on_the_circle(frequency, system.dt));
    ASSERT_TRUE(z.has_value()) << what;
    const Complex dense = nearest(all, *z);
    EXPECT_EQ(dense, nearest(all, on_the_circle(frequency, system.dt)))
        << what << ": it found the root nearest the guess";
    const double angle = std::arg(dense);
    EXPECT_NEAR(root_frequency(*z, system.dt) / root_frequency(dense, system.dt), 1.0,
                1e-13 / angle)
        << what;
    EXPECT_LE(residual(system, *z), 2.0 * residual(system, dense)) << what;
}

void expect_the_dense_roots(const Model& model, double pitch, const std::string& name) {
    const LinearSystem system = assemble_linear_system(model, "audio");
    const UpdateRoots all = update_roots(system);
    ASSERT_TRUE(all.converged) << name;
    for (const double partial : {1.0, 2.0, 3.0, 9.0})
        expect_the_dense_root(system, all, pitch * partial,
                              name + " near " + std::to_string(pitch * partial) + " Hz");
}

TEST(UpdateRootNear, IsTheDenseSolvesRootNearestTheGuess) {
    // Strings with the violin body (homogeneous and harmonic), the paper's chaplet (link damping
    // alone, heavy damped bridges), each with its bow's pressure buffer as if in contact; the
    // first partials, where a tuning looks, and a high one.
    for (const std::string pitch : {"220", "440"}) {
        const std::string name = "bowed-string-" + pitch + (pitch == "440" ? "-harmonic" : "");
        expect_the_dense_roots(load_model_file(test::resource("models/" + name + ".json")),
                               std::stod(pitch), name);
    }
    // On chains (the refinement's tridiagonal solve): the paper's, and a string without a body
    // (its losses to the rest points, heavy damped bridges).
    const Model paper = load_model_file(test::resource("models/bowed-string-110-paper.json"));
    ASSERT_TRUE(is_tridiagonal(assemble_linear_system(paper, "audio")));
    expect_the_dense_roots(paper, 110, "bowed-string-110-paper");
    BowedStringOptions o;
    o.pitch = 98, o.masses = 120, o.body = "none", o.with_gesture = false;
    const Model bare = build_bowed_string(o);
    ASSERT_TRUE(is_tridiagonal(assemble_linear_system(bare, "audio")));
    expect_the_dense_roots(bare, o.pitch, "98 Hz without a body");
}

// A coefficient that is not a number gives no root, on a chain as elsewhere: not the guess, as
// a shift exactly on a root would.
TEST(UpdateRootNear, FindsNoRootWhereACoefficientIsNotANumber) {
    const Model model = load_model_file(test::resource("models/bowed-string-110-paper.json"));
    LinearSystem system = assemble_linear_system(model, "audio");
    ASSERT_TRUE(is_tridiagonal(system));
    system.stiffness.coeffRef(5, 5) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(update_root_near(system, on_the_circle(110, system.dt)).has_value());
}

TEST(UpdateRootNear, LeavesAFingeredStringToTheDenseSolve) {
    BowedStringOptions o;
    o.pitch = 440, o.masses = 40, o.finger = true, o.finger_position = 0.75, o.with_gesture = false;
    const LinearSystem system = assemble_linear_system(build_bowed_string(o), "audio");
    ASSERT_FALSE(system.fingers.empty());
    EXPECT_FALSE(update_root_near(system, on_the_circle(440, system.dt)).has_value());
}

}  // namespace
}  // namespace archet
