// A homogeneous fixed–fixed chain against the dispersion formula of the discrete scheme:
// sin(Ω_k·T/2) = √(K·T²/M)·sin(kπ/(2(N+1))) (physics.md §2).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/model/linear_system.hpp"
#include "archet/physics/compiled_model.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

constexpr double kFs = 48000, kDt = 1 / kFs, kMass = 1e-4, kNormalisedK = 0.6;
constexpr int kN = 30;

double dispersion(int k) {
    const double s = std::sqrt(kNormalisedK) * std::sin(k * std::numbers::pi / (2.0 * (kN + 1)));
    return 2.0 * std::asin(s) / (2.0 * std::numbers::pi * kDt);
}

TEST(ChainModes, ModalAnalysisMatchesTheDispersionFormula) {
    const Model model = test::chain(kN, kMass, kNormalisedK * kMass / (kDt * kDt), 0.0, kFs);
    const auto modes = discrete_modes(assemble_linear_system(model));
    ASSERT_EQ(modes.size(), static_cast<std::size_t>(kN));
    for (int k = 1; k <= kN; ++k)
        EXPECT_NEAR(modes[k - 1].frequency / dispersion(k), 1.0, 1e-10) << "mode " << k;
}

class ChainModeSimulation : public ::testing::TestWithParam<int> {};

TEST_P(ChainModeSimulation, AStringStartedInOneModeOscillatesAtItsDiscreteFrequency) {
    const int k = GetParam();
    Model model = test::chain(kN, kMass, kNormalisedK * kMass / (kDt * kDt), 0.0, kFs);
    const double omega_t = 2 * std::numbers::pi * dispersion(k) * kDt;
    // x[0] = shape, x[−1] = shape·cos(ΩT): a pure standing wave of mode k.
    for (int i = 1; i <= kN; ++i) {
        Mat& m = model.mats[i];
        const double shape = 1e-3 * std::sin(i * k * std::numbers::pi / (kN + 1));
        m.position = shape;
        m.velocity = (shape - shape * std::cos(omega_t)) / kDt;
    }
    Simulation sim(compile(model));
    std::vector<double> projection;
    double leak = 0;
    for (int step = 0; step < 20000; ++step) {
        sim.step();
        double along = 0, total = 0;
        for (int i = 1; i <= kN; ++i) {
            const double x = sim.position(sim.model().mat_slots.at("m" + std::to_string(i)));
            along += x * std::sin(i * k * std::numbers::pi / (kN + 1));
            total += x * x;
        }
        along *= 2.0 / (kN + 1);
        projection.push_back(along);
        // Whatever is not mode k would be another mode: there must be none.
        leak = std::max(leak, std::abs(total - along * along * (kN + 1) / 2.0));
    }
    EXPECT_NEAR(test::sinusoid_frequency(projection, kFs) / dispersion(k), 1.0, 1e-9);
    EXPECT_LT(leak, 1e-18);
}

INSTANTIATE_TEST_SUITE_P(Modes, ChainModeSimulation, ::testing::Values(1, 2, 5, 15, 29));

TEST(ChainModes, HomogeneousChainIsInharmonicAndFlat) {
    // physics.md: N = 40 at 220 Hz puts partial 10 about 36 cents flat.
    const int n = 40;
    const double f0 = 220;
    const double ratio =
        std::sin(std::numbers::pi * f0 * kDt) / std::sin(std::numbers::pi / (2.0 * (n + 1)));
    const Model model = test::chain(n, kMass, ratio * ratio * kMass / (kDt * kDt), 0.0, kFs);
    const auto modes = discrete_modes(assemble_linear_system(model));
    EXPECT_NEAR(modes[0].frequency, f0, 1e-9);
    const double cents10 = 1200 * std::log2(modes[9].frequency / (10 * f0));
    EXPECT_NEAR(cents10, -36, 3);
}

}  // namespace
}  // namespace archet
