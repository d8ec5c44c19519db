// The single damped oscillator of the CORDIS scheme against its closed-form discrete
// frequency and decay (physics.md §1), and against the modal analysis.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/model/linear_system.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/compiled_model.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

struct Case {
    double k_normalised, z_normalised;
};

class OscillatorTest : public ::testing::TestWithParam<Case> {};

Model oscillator(double fs, double m, double k, double z) {
    Model model;
    model.sample_rate = fs;
    Mat osc;
    osc.id = "osc", osc.kind = MatKind::Oscillator, osc.rate = "audio";
    osc.mass = m, osc.stiffness = k, osc.damping = z, osc.position = 0, osc.velocity = 0.5;
    model.mats.push_back(osc);
    model.probes.push_back({"x", ProbeKind::Position, "osc"});
    return model;
}

TEST_P(OscillatorTest, FrequencyAndDecayMatchTheDiscreteFormula) {
    const double fs = 48000, dt = 1 / fs, m = 2e-3;
    const auto [K, Z] = GetParam();
    const Model model = oscillator(fs, m, K * m / (dt * dt), Z * m / dt);
    validate_model(model);
    Simulation sim(compile(model));
    std::vector<double> x;
    // Record until the envelope has fallen by about 20 nepers (long before it underflows).
    const int steps =
        Z > 0 ? static_cast<int>(std::min(200000.0, 20.0 / (-0.5 * std::log(1 - Z)))) : 200000;
    for (int i = 0; i < steps; ++i) sim.step(), x.push_back(sim.probe(0));

    // f = fs/(2π)·acos((2 − (K+Z)) / (2·√(1−Z))); the roots of z² − (2−K−Z)z + (1−Z) have
    // |z| = √(1−Z).
    const double expected =
        fs / (2 * std::numbers::pi) * std::acos((2 - (K + Z)) / (2 * std::sqrt(1 - Z)));
    const double expected_radius = std::sqrt(1 - Z);

    // What the simulation did: the two-term recurrence that fits its output by least squares,
    // x[n+1] = a·x[n] + b·x[n−1], gives its frequency and decay per step.
    double xx = 0, xy = 0, yy = 0, tx = 0, ty = 0;  // x = x[n], y = x[n−1], t = x[n+1]
    for (std::size_t n = 1; n + 1 < x.size(); ++n)
        xx += x[n] * x[n], xy += x[n] * x[n - 1], yy += x[n - 1] * x[n - 1], tx += x[n + 1] * x[n],
            ty += x[n + 1] * x[n - 1];
    const double det = xx * yy - xy * xy;
    const double a = (tx * yy - ty * xy) / det, b = (ty * xx - tx * xy) / det;
    const double radius = std::sqrt(-b);
    const double frequency = fs / (2 * std::numbers::pi) * std::acos(a / (2 * radius));
    EXPECT_NEAR(frequency / expected, 1.0, 1e-9);
    EXPECT_NEAR(radius, expected_radius, 1e-10);
    // And counted the slow way, by zero crossings, where there are many samples per period.
    if (expected < fs / 20) {
        EXPECT_NEAR(test::zero_crossing_frequency(x, fs) / expected, 1.0, 1e-6);
    }

    const auto modes = discrete_modes(assemble_linear_system(model));
    ASSERT_EQ(modes.size(), 1u);
    EXPECT_NEAR(modes[0].frequency / expected, 1.0, 1e-12);
    EXPECT_NEAR(modes[0].radius, expected_radius, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(NormalisedStiffnessAndDamping, OscillatorTest,
                         ::testing::Values(Case{0.001, 0.0}, Case{0.05, 0.0001}, Case{0.5, 0.001},
                                           Case{2.0, 0.01}, Case{3.5, 0.0}));

}  // namespace
}  // namespace archet
