// Harmonic retuning: the inverse eigenvalue problem, the harmonic chaplets at the paper's
// pitches (their simulated partials on k·f0 within a cent), its limits, and the paper's
// Fig. 2: a harmonic string settles into Helmholtz motion sooner than a homogeneous one.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "archet/analysis/bowing_analysis.hpp"
#include "archet/analysis/modal_analysis.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/builders/harmonic_chain.hpp"
#include "archet/builders/string_chain.hpp"
#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/stability.hpp"
#include "archet/physics/compiled_model.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

TEST(HarmonicChain, InverseProblemRecoversTheSpectrum) {
    const int n = 40;
    std::vector<double> lambda;
    for (int k = 1; k <= n; ++k)
        lambda.push_back(1e6 * k * k * (1 + 0.01 * std::sin(k)));  // any increasing set
    const ChainProfile c = chain_with_eigenvalues(lambda, 2e-3);
    ASSERT_EQ(c.masses.size(), static_cast<std::size_t>(n));
    ASSERT_EQ(c.springs.size(), static_cast<std::size_t>(n + 1));
    double total = 0;
    Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
        EXPECT_GT(c.masses[i], 0);
        EXPECT_GT(c.springs[i], 0);
        total += c.masses[i];
        k(i, i) = c.springs[i] + c.springs[i + 1];
        if (i + 1 < n) k(i, i + 1) = k(i + 1, i) = -c.springs[i + 1];
    }
    EXPECT_NEAR(total, 2e-3, 1e-15);
    Eigen::VectorXd s(n);
    for (int i = 0; i < n; ++i) s[i] = 1 / std::sqrt(c.masses[i]);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(s.asDiagonal() * k * s.asDiagonal());
    for (int i = 0; i < n; ++i) EXPECT_NEAR(solver.eigenvalues()[i] / lambda[i], 1.0, 1e-10);
    // Mirror symmetric, as the spectral weights assume.
    for (int i = 0; i < n; ++i) EXPECT_NEAR(c.masses[i] / c.masses[n - 1 - i], 1.0, 1e-8);
}

// The full-bandwidth search steps down on the string tuned on its undamped modes, for a
// fraction of the full tuning's time: it must use the stability limit as the fully tuned string
// does, to well within the step from one mass count to the next (here the strings alone, the
// search's with the bow).
TEST(HarmonicChain, TheUndampedTuningUsesTheStabilityLimitAsTheFullTuningDoes) {
    BowedStringOptions o;
    o.pitch = 220;
    o.tuning = Tuning::Harmonic;
    ASSERT_TRUE(tuning_ends_on_damped_modes(o));
    const auto use = [](const Model& m) {
        double worst = 0;
        for (const auto& r : analyse_stability(m))
            worst = std::max(worst, r.largest_eigenvalue / StabilityReport::kLimit);
        return worst;
    };
    const double full_96 = use(tuned_string(o, 96)), full_97 = use(tuned_string(o, 97));
    const double undamped_96 = use(undamped_tuned_string(o, 96));
    const double undamped_97 = use(undamped_tuned_string(o, 97));
    ASSERT_GT(full_97 - full_96, 0.002);
    EXPECT_LT(std::abs(undamped_96 - full_96), 0.25 * (full_97 - full_96));
    EXPECT_LT(std::abs(undamped_97 - full_97), 0.25 * (full_97 - full_96));
    EXPECT_NE(undamped_96, full_96);  // the damped steps did run in the full tuning
    // No damped steps to leave out: a homogeneous string, or one damped while it is tuned.
    o.tuning = Tuning::Homogeneous;
    EXPECT_FALSE(tuning_ends_on_damped_modes(o));
    o.tuning = Tuning::Harmonic;
    o.paper = true;
    EXPECT_FALSE(tuning_ends_on_damped_modes(o));
}

class HarmonicString : public ::testing::TestWithParam<int> {};

TEST_P(HarmonicString, SimulatedPartialsAreHarmonicWithinACent) {
    if (test::kUnderSanitizer && GetParam() == 110)
        GTEST_SKIP() << test::kLargeStringUnderSanitizer;
    BowedStringOptions o;  // full bandwidth; a body would pull the partials near its modes
    o.pitch = GetParam(), o.tuning = Tuning::Harmonic, o.body = "none", o.with_gesture = false;
    const Model model = build_bowed_string(o);
    validate_model(model);
    const ModalAnalysis modes = analyse_modes(model);
    int partials = 0;
    for (const auto& m : modes.modes) {
        if (m.support) continue;
        ++partials;
        // Tuned undamped; the losses then pull the highest partials by a cent or so.
        EXPECT_LT(std::abs(1200 * std::log2(m.frequency / (m.partial * o.pitch))),
                  m.partial <= 20 ? 0.1 : 2.0)
            << "partial " << m.partial;
    }
    int masses = 0;
    for (const auto& m : model.mats)
        masses += m.kind != MatKind::ModalPoint && m.id[0] == 's' && std::isdigit(m.id[1]);
    EXPECT_EQ(partials, masses) << "every partial of the chaplet";
    EXPECT_LT(masses * o.pitch, o.sample_rate / 2);
    EXPECT_GE(masses, 0.8 * max_harmonic_masses(o.pitch, o.sample_rate)) << "full bandwidth";
}

TEST_P(HarmonicString, ShippedVariantIsWhatTheBuilderMakes) {
    if (test::kUnderSanitizer && GetParam() == 110)
        GTEST_SKIP() << test::kLargeStringUnderSanitizer;
    BowedStringOptions o;
    o.pitch = GetParam(), o.tuning = Tuning::Harmonic;
    const auto path =
        test::resource("models/bowed-string-" + std::to_string(GetParam()) + "-harmonic.json");
    EXPECT_EQ(format_model(build_bowed_string(o)), test::read_file(path))
        << "regenerate with: archet new bowed-string --tuning harmonic --pitch " << GetParam();
}

INSTANTIATE_TEST_SUITE_P(PaperPitches, HarmonicString, ::testing::Values(110, 220, 440, 880));

TEST(HarmonicString, RefusesPartialsAtOrAboveHalfTheSampleRate) {
    BowedStringOptions o;
    o.pitch = 440, o.tuning = Tuning::Harmonic, o.masses = 55;  // 55·440 = 24200 Hz ≥ 24000 Hz
    try {
        build_bowed_string(o);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("at most 54 masses"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("fs/2"), std::string::npos) << e.what();
    }
    EXPECT_EQ(max_harmonic_masses(440, 48000), 54);
    EXPECT_EQ(max_harmonic_masses(480, 48000), 49) << "50·480 Hz would sit exactly on fs/2";
}

// Time from first contact to steady Helmholtz motion with the steady-bow gesture.
AttackAnalysis attack_of(const std::string& file) {
    const Model model = load_model_file(test::resource("models/" + file));
    const Gesture steady = load_gesture_file(test::resource("gestures/steady-bow.json"));
    Simulation sim(compile(model));
    sim.set_gesture_track(&steady);
    std::vector<double> slip, normal;
    for (int i = 0; i < 2.7 * 48000; ++i) {
        sim.step();
        slip.push_back(sim.model().bows[0].slip_velocity);
        normal.push_back(sim.model().bows[0].normal);
    }
    return analyse_attack(slip, normal, 48000, analyse_modes(model).fundamental);
}

class Attack : public ::testing::TestWithParam<int> {};

TEST_P(Attack, HarmonicStringReachesHelmholtzMotionSooner) {
    const std::string pitch = std::to_string(GetParam());
    // The paper's claim, on its strings with the shipped steady stroke.
    const AttackAnalysis homogeneous = attack_of("bowed-string-" + pitch + "-paper.json");
    const AttackAnalysis harmonic = attack_of("bowed-string-" + pitch + "-harmonic-paper.json");
    ASSERT_TRUE(homogeneous.reached());
    ASSERT_TRUE(harmonic.reached());
    EXPECT_LT(harmonic.attack(), 0.8 * homogeneous.attack())
        << "harmonic " << harmonic.attack() << " s, homogeneous " << homogeneous.attack() << " s";
    // And its steady period is the first mode's, where the homogeneous one runs flat.
    EXPECT_NEAR(1200 * std::log2(1 / (harmonic.period * GetParam())), 0.0, 5.0);
}

INSTANTIATE_TEST_SUITE_P(PaperPitches, Attack, ::testing::Values(110, 220, 440));

}  // namespace
}  // namespace archet
