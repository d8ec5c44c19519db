// analyse_modes() takes each mode's shape from its root, by an inverse iteration a mode, rather
// than from the dense solve's eigenvectors: the same modes, held here to the eigenvectors' on
// every shipped string and on strings the builder makes (the roots, frequencies, decays, classes
// and cents to the bit, the shapes to rounding), with more passes where two fall short, and the
// dense solve itself where a shape cannot be told from its root alone.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/mode_shape.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/linear_system.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

// Bits of a double, so that a difference in the last one fails.
std::uint64_t bits(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

// The largest difference between two shapes of one mode, each scaled to a largest entry of 1
// by class_modes(), up to their sign (the sign of a mode is arbitrary).
double shape_difference(const std::vector<double>& a, const std::vector<double>& b) {
    double same = 0, opposite = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        same = std::max(same, std::abs(a[i] - b[i]));
        opposite = std::max(opposite, std::abs(a[i] + b[i]));
    }
    return std::min(same, opposite);
}

void expect_the_eigenvectors_modes(const LinearSystem& sys, const Model& model,
                                   const std::string& what) {
    const std::optional<ModalSolve> from_roots = solve_modes_from_roots(sys);
    ASSERT_TRUE(from_roots.has_value()) << what << ": its shapes came from the dense solve";
    const ModalAnalysis fast = class_modes(*from_roots, sys, model);
    const ModalAnalysis dense = class_modes(solve_modes_with_eigenvectors(sys), sys, model);
    ASSERT_EQ(fast.modes.size(), dense.modes.size()) << what;
    ASSERT_FALSE(fast.modes.empty()) << what;
    EXPECT_EQ(bits(fast.fundamental), bits(dense.fundamental)) << what;
    double worst = 0;
    for (std::size_t m = 0; m < fast.modes.size(); ++m) {
        const ModeInfo &f = fast.modes[m], &d = dense.modes[m];
        EXPECT_EQ(bits(f.frequency), bits(d.frequency)) << what << ", mode " << m;
        EXPECT_EQ(bits(f.t60), bits(d.t60)) << what << ", mode " << m;
        EXPECT_EQ(f.support, d.support) << what << ", mode " << m << " at " << f.frequency;
        EXPECT_EQ(f.partial, d.partial) << what << ", mode " << m;
        EXPECT_EQ(bits(f.cents), bits(d.cents)) << what << ", mode " << m;
        worst = std::max(worst, shape_difference(f.shape, d.shape));
    }
    EXPECT_LT(worst, 1e-7) << what << ": shapes of one mode, each largest entry 1";
}

TEST(ModeShapesFromRoots, AreTheEigenvectorsModesOnEveryShippedString) {
    int strings = 0;
    for (const auto& entry : std::filesystem::directory_iterator(test::resource("models"))) {
        if (entry.path().extension() != ".json") continue;
        const Model model = load_model_file(entry.path());
        expect_the_eigenvectors_modes(sounding_part(model), model, entry.path().filename());
        ++strings;
    }
    EXPECT_GE(strings, 16);
}

TEST(ModeShapesFromRoots, AreTheEigenvectorsModesOnBuiltStrings) {
    // A cello's C with its body and without (a sparse pencil, and a chain), a bow near the
    // bridge, a harmonic string and the paper's 880 Hz chaplet.
    std::vector<BowedStringOptions> all;
    BowedStringOptions cello;
    cello.pitch = 65.41, cello.tension = 130, cello.linear_density = 0.0148;
    all.push_back(cello);
    cello.body = "none";
    all.push_back(cello);
    BowedStringOptions o;
    o.pitch = 440, o.bow_position = 0.05;
    all.push_back(o);
    o = {};
    o.pitch = 220, o.tuning = Tuning::Harmonic;
    all.push_back(o);
    o = {};
    o.pitch = 880, o.paper = true;
    all.push_back(o);
    for (const BowedStringOptions& options : all) {
        const Model model = build_bowed_string(options);
        expect_the_eigenvectors_modes(sounding_part(model), model,
                                      "the " + std::to_string(options.pitch) + " Hz string");
    }
}

// Two like oscillators side by side, joined by a spring `coupling` (N/m).
LinearSystem two_oscillators(double coupling) {
    LinearSystem sys;
    sys.rate = "audio", sys.dt = 1.0 / 48000, sys.dofs = {"a", "b"};
    sys.mass = Eigen::VectorXd::Constant(2, 0.001);
    sys.stiffness.resize(2, 2), sys.damping.resize(2, 2);
    sys.stiffness.insert(0, 0) = 1000 + coupling, sys.stiffness.insert(1, 1) = 1000 + coupling;
    if (coupling != 0)
        sys.stiffness.insert(0, 1) = -coupling, sys.stiffness.insert(1, 0) = -coupling;
    sys.damping.insert(0, 0) = 0.001, sys.damping.insert(1, 1) = 0.001;
    return sys;
}

// Roots at one frequency, or too close for their shapes to be told apart to 1e−9 (any mix of
// the two is nearly a shape of each), take the dense solve, its modes to the bit; a coupling
// that parts them far enough does not.
TEST(ModeShapesFromRoots, RootsTooCloseToTellApartTakeTheDenseSolve) {
    for (double coupling : {0.0, 1e-9, 1e-6}) {
        const LinearSystem sys = two_oscillators(coupling);
        EXPECT_FALSE(solve_modes_from_roots(sys).has_value()) << "coupling " << coupling;
        const ModalSolve solve = solve_modes(sys), dense = solve_modes_with_eigenvectors(sys);
        ASSERT_EQ(solve.roots.size(), 2);
        EXPECT_EQ(solve.roots, dense.roots);
        EXPECT_EQ(solve.shapes, dense.shapes);
    }
    EXPECT_TRUE(solve_modes_from_roots(two_oscillators(10.0)).has_value());
}

// A finger's force is in the update, not in the pencil: a fingered string takes the dense solve.
TEST(ModeShapesFromRoots, AFingeredStringTakesTheDenseSolve) {
    BowedStringOptions o;
    o.pitch = 440, o.finger = true, o.finger_position = 0.75;
    const Model model = build_bowed_string(o);
    const LinearSystem sys = sounding_part(model);
    ASSERT_FALSE(sys.fingers.empty());
    EXPECT_FALSE(solve_modes_from_roots(sys).has_value());
    const ModalSolve solve = solve_modes(sys), dense = solve_modes_with_eigenvectors(sys);
    EXPECT_EQ(solve.roots, dense.roots);
    EXPECT_EQ(solve.shapes, dense.shapes);
}

// The largest distance between two complex shapes, each scaled to unit length and turned to
// the other's phase.
double shape_distance(Eigen::VectorXcd a, Eigen::VectorXcd b) {
    a.normalize(), b.normalize();
    std::complex<double> phase = b.dot(a);
    phase /= std::abs(phase);
    return (a - b * phase).cwiseAbs().maxCoeff();
}

// On the paper's 110 Hz string two passes of inverse iteration leave some shape well off its
// eigenvector (the bridge's mode beside the nut's); the analysis passes again until none is.
TEST(ModeShapesFromRoots, PassAgainWhereTwoPassesFallShort) {
    const Model model = load_model_file(test::resource("models/bowed-string-110-paper.json"));
    const LinearSystem sys = sounding_part(model);
    const std::optional<ModalSolve> from_roots = solve_modes_from_roots(sys);
    ASSERT_TRUE(from_roots.has_value());
    const ModalSolve dense = solve_modes_with_eigenvectors(sys);
    double two_passes = 0, analysis = 0;
    for (Eigen::Index k = 0; k < dense.roots.size(); ++k) {
        const auto shape = mode_shape(sys, dense.roots[k], 2);
        ASSERT_TRUE(shape.has_value());
        const Eigen::VectorXcd v = Eigen::Map<const Eigen::VectorXcd>(shape->data(), sys.size());
        two_passes = std::max(two_passes, shape_distance(v, dense.shapes.col(k)));
        analysis =
            std::max(analysis, shape_distance(from_roots->shapes.col(k), dense.shapes.col(k)));
    }
    EXPECT_GT(two_passes, 1e-6);
    EXPECT_LT(analysis, 1e-9);
}

}  // namespace
}  // namespace archet
