// The body: body modes coupled at the bridge. The string with a body shows the body's
// resonances among its modes; the bridge's driving-point admittance is the modal sum of the
// preset; the radiated sound is at the level of the bridge force it replaces.

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/builders/string_body.hpp"
#include "archet/common/input_error.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/stability.hpp"
#include "archet/physics/compiled_model.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

Model violin_string(Structure structure, bool with_gesture = false) {
    BowedStringOptions o;  // the builder attaches the violin body by default
    o.pitch = 220, o.structure = structure, o.with_gesture = with_gesture;
    EXPECT_EQ(o.body, "violin");
    return build_bowed_string(o);
}

// Y(ω) = Σ jω / (m_k·(ω_k² − ω² + 2jζ_k·ω_k·ω)), the standard modal sum, m/(N·s).
std::complex<double> modal_admittance(const BodyPreset& body, double f) {
    const double w = 2 * std::numbers::pi * f;
    std::complex<double> y = 0;
    for (const auto& m : body.modes) {
        const double wk = 2 * std::numbers::pi * m.frequency;
        y += std::complex<double>(0, w) /
             (m.effective_mass *
              std::complex<double>(wk * wk - w * w, 2 * m.damping_ratio * wk * w));
    }
    return y;
}

class BodyOnString : public ::testing::TestWithParam<Structure> {};

TEST_P(BodyOnString, ModesShowTheBodyResonances) {
    const Model model = violin_string(GetParam());
    const ModalAnalysis analysis = analyse_modes(model);
    for (const auto& mode : find_body_preset("violin").modes) {
        // The scheme's modes are damped: they ring at f·√(1 − ζ²).
        const double expected =
            mode.frequency * std::sqrt(1 - mode.damping_ratio * mode.damping_ratio);
        const ModeInfo* nearest = nullptr;
        for (const auto& m : analysis.modes)
            if (!nearest ||
                std::abs(m.frequency - expected) < std::abs(nearest->frequency - expected))
                nearest = &m;
        ASSERT_NE(nearest, nullptr);
        EXPECT_NEAR(nearest->frequency / expected, 1.0, 0.03) << mode.frequency << " Hz";
        // The broad bridge-hill modes share their motion with the string's partials nearby.
        if (mode.damping_ratio < 0.05) {
            EXPECT_TRUE(nearest->support) << mode.frequency << " Hz is a mode of the body";
        }
    }
    // The builder tunes the string with its body: its first mode is the pitch.
    EXPECT_NEAR(1200 * std::log2(analysis.fundamental / 220.0), 0.0, 1.0);
}

TEST_P(BodyOnString, StaysStableAndRadiatesAtTheBridgeForceLevel) {
    const Model model = violin_string(GetParam(), true);  // with the stroke in its band
    for (const auto& r : analyse_stability(model)) EXPECT_TRUE(r.stable()) << r.rate;
    Simulation sim(compile(model));
    double peak = 0;
    for (int i = 0; i < 2 * 48000; ++i) sim.step(), peak = std::max(peak, std::abs(sim.output()));
    const double dbfs = 20 * std::log10(peak);
    EXPECT_GT(dbfs, -12.0) << "a bowed note is clearly audible";
    EXPECT_LT(dbfs, -3.0) << "and well below full scale";
}

INSTANTIATE_TEST_SUITE_P(Structures, BodyOnString,
                         ::testing::Values(Structure::Chain, Structure::Modal));

TEST(Body, BridgeAdmittanceIsTheModalSum) {
    // The body alone: an impulse of force I on the bridge point gives each mode the velocity
    // I/m_k; the bridge's velocity response, Fourier-transformed, is I·Y(ω).
    Model model;
    model.sample_rate = 48000;
    Mat bridge;
    bridge.id = "bridge", bridge.kind = MatKind::Oscillator, bridge.mass = 0.01,
    bridge.stiffness = 100, bridge.damping = 1;
    model.mats.push_back(bridge);
    const BodyPreset& body = find_body_preset("violin");
    attach_body(model, body);
    const double impulse = 1e-3;  // N·s
    for (auto& m : model.mats)
        if (m.kind == MatKind::Oscillator) m.velocity = impulse / m.mass;
    model.probes = {{"bridge_v", ProbeKind::Velocity, "bridge"}};
    Simulation sim(compile(model));
    const double dt = 1 / model.sample_rate;
    // The scheme's velocity (x[n] − x[n−1])/T is the motion at (n − ½)·T: a midpoint rule.
    std::vector<double> response;
    for (int i = 0; i < 48000; ++i) sim.step(), response.push_back(sim.probe(0));
    auto measured = [&](double f) {
        std::complex<double> sum = 0;
        for (std::size_t n = 0; n < response.size(); ++n)
            sum += response[n] * std::polar(1.0, -2 * std::numbers::pi * f * (n + 0.5) * dt);
        return sum * dt / impulse;
    };
    // At each mode's frequency, where the admittance peaks, the modal sum: within 3 % for the
    // signature modes and 15 % for the broad bridge-hill modes (ζ = 0.1, where the scheme's
    // backward-difference damper departs from the continuous one). Between modes, near the
    // anti-resonances where the signature modes' mass-like and the hill's spring-like parts
    // cancel, the small admittance is within 25 %.
    for (const auto& m : body.modes) {
        const double tolerance = m.damping_ratio < 0.05 ? 0.03 : 0.15;
        EXPECT_NEAR(std::abs(measured(m.frequency)) / std::abs(modal_admittance(body, m.frequency)),
                    1.0, tolerance)
            << m.frequency << " Hz";
    }
    for (double f : {150.0, 350.0, 700.0, 1000.0, 3000.0})
        EXPECT_NEAR(std::abs(measured(f)) / std::abs(modal_admittance(body, f)), 1.0, 0.25)
            << f << " Hz";
    // Peaks of the size the preset says: 1/(2ζmω) at B1+, within the neighbours' share.
    const auto& b1 = body.modes[3];
    EXPECT_NEAR(
        std::abs(modal_admittance(body, b1.frequency)) *
            (2 * b1.damping_ratio * b1.effective_mass * 2 * std::numbers::pi * b1.frequency),
        1.0, 0.3);
}

TEST(Body, UnknownNameIsRefusedNamingThePresets) {
    try {
        find_body_preset("theorbo");
        ADD_FAILURE() << "accepted an unknown body";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "--body");
        EXPECT_NE(e.message().find("theorbo"), std::string::npos) << e.what();
        for (const auto& p : body_presets())
            EXPECT_NE(e.message().find(p.name), std::string::npos) << e.what();
        EXPECT_NE(e.message().find("none"), std::string::npos) << e.what();
    }
}

TEST(Body, EveryPresetCitesItsSourceAndIsPhysical) {
    ASSERT_FALSE(body_presets().empty());
    for (const auto& p : body_presets()) {
        EXPECT_FALSE(p.source.empty()) << p.name;
        EXPECT_GE(p.modes.size(), 4u) << p.name;
        for (const auto& m : p.modes) {
            EXPECT_GT(m.frequency, 0) << p.name;
            EXPECT_LT(m.frequency, 20000) << p.name;
            EXPECT_GT(m.damping_ratio, 0) << p.name;
            EXPECT_LT(m.damping_ratio, 1) << p.name;
            EXPECT_GT(m.effective_mass, 0) << p.name;
        }
    }
}

TEST(Body, MissingBridgeIsRefused) {
    Model model = violin_string(Structure::Chain);
    EXPECT_THROW(attach_body(model, find_body_preset("violin"), "tailpiece"), InputError);
}

}  // namespace
}  // namespace archet
