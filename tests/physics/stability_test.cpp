// The stability bound: the largest eigenvalue of M^-½(K·T² + 2·Z·T)M^-½ against its closed
// form for chains, exact below a few hundred DOFs and by Lanczos above; validation refuses a
// model past the bound and the simulation of such a model really does blow up.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "archet/builders/bowed_string.hpp"
#include "archet/common/input_error.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/stability.hpp"
#include "archet/model/stability_limit.hpp"
#include "archet/physics/compiled_model.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

constexpr double kFs = 48000, kDt = 1 / kFs, kMass = 1e-4;

double chain_bound(int n, double k_normalised, double z_normalised) {
    // Eigenvalues of the fixed–fixed chain: 4(K+2Z)·sin²(jπ/(2(N+1))).
    return 4 * (k_normalised + 2 * z_normalised) *
           std::pow(std::sin(n * std::numbers::pi / (2.0 * (n + 1))), 2);
}

class ChainBound : public ::testing::TestWithParam<int> {};

TEST_P(ChainBound, LargestEigenvalueMatchesTheClosedForm) {
    const int n = GetParam();
    const double K = 0.7, Z = 0.01;
    const Model model = test::chain(n, kMass, K * kMass / (kDt * kDt), Z * kMass / kDt, kFs);
    const auto reports = analyse_stability(model);
    ASSERT_EQ(reports.size(), 1u);
    const double expected = chain_bound(n, K, Z);
    EXPECT_GE(reports[0].largest_eigenvalue, expected * (1 - 1e-9))
        << "must not understate the bound";
    // Exact from the dense solver; Lanczos gives its Ritz value plus the residual bound, a
    // safe upper estimate that is tight for well separated spectra and within 0.2 % for
    // the clustered top of a long chain.
    EXPECT_NEAR(reports[0].largest_eigenvalue / expected, 1.0, n <= 400 ? 1e-9 : 2e-3);
}

// 60 and 300 use the dense solver; 5000 Lanczos.
INSTANTIATE_TEST_SUITE_P(Sizes, ChainBound, ::testing::Values(60, 300, 5000));

TEST(Stability, ValidationRefusesAModelPastTheBoundNamingTheStiffestMass) {
    Model model = test::chain(20, kMass, 1.02 * kMass / (kDt * kDt), 0.0, kFs);
    try {
        validate_model(model);
        FAIL() << "accepted an unstable chain";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("unstable"), std::string::npos) << what;
        EXPECT_NE(what.find("mass \"m"), std::string::npos) << what;
        EXPECT_NE(what.find("below 4"), std::string::npos) << what;
    }
}

TEST(Stability, TheBoundIsWhereTheSchemeReallyBlowsUp) {
    // Just inside: bounded for ever. Just outside: grows without bound.
    for (double K : {0.99, 1.01}) {
        Model model = test::chain(20, kMass, K * kMass / (kDt * kDt), 0.0, kFs);
        model.mats[5].position = 1e-6;
        Simulation sim(compile(model));
        double peak = 0;
        for (int i = 0; i < 200000; ++i) {
            sim.step();
            peak = std::max(peak, std::abs(sim.position(sim.model().mat_slots.at("m5"))));
        }
        const bool stable = analyse_stability(model)[0].stable();
        if (stable)
            EXPECT_LT(peak, 1e-5) << "K=" << K;
        else
            EXPECT_GT(peak, 1.0) << "K=" << K;
    }
}

TEST(Stability, BuilderRefusesPitchesWithoutAStableChaplet) {
    BowedStringOptions o;
    o.pitch = 2000, o.paper = true;  // the paper's chaplets have 25 masses or more
    try {
        build_bowed_string(o);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("at most 11 masses"), std::string::npos) << e.what();
    }
    o.pitch = 440, o.masses = 60;  // physics.md: 60 masses at 440 Hz is unstable
    EXPECT_THROW(build_bowed_string(o), InputError);
    EXPECT_EQ(max_stable_masses(440, 48000), 53);
    EXPECT_EQ(max_stable_masses(880, 48000), 26);
}

}  // namespace
}  // namespace archet

namespace archet {
namespace {

// One damped oscillator: stable while K + 2Z < 4 with K = k·T²/m and Z = z·T/m.
Model lone_oscillator(double m, double k, double z) {
    Model model;
    Mat osc;
    osc.id = "osc", osc.kind = MatKind::Oscillator, osc.mass = m, osc.stiffness = k,
    osc.damping = z;
    model.mats = {osc};
    return model;
}

TEST(StabilityLimit, MatchesTheClosedFormOfAnOscillator) {
    const double m = 0.01, k = 1e5, z = 0.5, T = 1.0 / 48000;
    const Model model = lone_oscillator(m, k, z);
    const auto stiffness = stability_limit(model, {"osc", "stiffness"});
    ASSERT_TRUE(stiffness);
    EXPECT_TRUE(stiffness->upper);
    EXPECT_NEAR(stiffness->value, (4 - 2 * z * T / m) * m / (T * T), 2e-6 * stiffness->value);
    const auto damping = stability_limit(model, {"osc", "damping"});
    ASSERT_TRUE(damping);
    EXPECT_NEAR(damping->value, (4 - k * T * T / m) * m / (2 * T), 2e-6 * damping->value);
    const auto mass = stability_limit(model, {"osc", "mass"});
    ASSERT_TRUE(mass);
    EXPECT_FALSE(mass->upper) << "a mass may only shrink so far";
    EXPECT_NEAR(mass->value, (k * T * T + 2 * z * T) / 4, 2e-6 * mass->value);
    EXPECT_EQ(mass->current, m);
    EXPECT_FALSE(stability_limit(model, {"osc", "position"})) << "not a stability parameter";
}

}  // namespace
}  // namespace archet
