// analyse_modes() takes each mode's shape from its root, by an inverse iteration a mode, rather
// than from the dense solve's eigenvectors: the same modes, held here to the eigenvectors' on
// every shipped string and on strings the builder makes (the roots, frequencies, decays, classes
// and cents to the bit, the shapes to rounding), and the dense solve itself where a shape cannot
// be told from its root alone.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "archet/analysis/modal_analysis.hpp"
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
    const ModalAnalysis fast = class_modes(solve_modes(sys), sys, model);
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
    // A cello's C without and with its body (a chain, and a sparse pencil), a point bow near the
    // bridge, a harmonic string and a stiff short one.
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

// Two roots at one frequency have no shape of their own (any mix of the two is one): two like
// oscillators side by side, unjoined, take the dense solve, its modes to the bit.
TEST(ModeShapesFromRoots, TwoRootsAtOneFrequencyTakeTheDenseSolve) {
    LinearSystem sys;
    sys.rate = "audio", sys.dt = 1.0 / 48000, sys.dofs = {"a", "b"};
    sys.mass = Eigen::VectorXd::Constant(2, 0.001);
    sys.stiffness.resize(2, 2), sys.damping.resize(2, 2);
    sys.stiffness.insert(0, 0) = 1000, sys.stiffness.insert(1, 1) = 1000;
    sys.damping.insert(0, 0) = 0.001, sys.damping.insert(1, 1) = 0.001;
    const ModalSolve fast = solve_modes(sys), dense = solve_modes_with_eigenvectors(sys);
    ASSERT_EQ(fast.roots.size(), 2);
    EXPECT_EQ(fast.roots, dense.roots);
    EXPECT_EQ(fast.shapes, dense.shapes);
}

}  // namespace
}  // namespace archet
