// The paper's parameter control function: a module that drives one element parameter from a
// signal, here an envelope and a gesture axis, clamped to its declared range.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "archet/common/input_error.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/compiled_model.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

constexpr double kFs = 48000, kDt = 1 / kFs, kMass = 1e-3;

double discrete_frequency(double k) {
    return kFs / (2 * std::numbers::pi) * std::acos((2 - k * kDt * kDt / kMass) / 2);
}

Model oscillator_with_control(Control control) {
    Model model;
    Mat osc;
    osc.id = "osc", osc.kind = MatKind::Oscillator, osc.mass = kMass, osc.stiffness = 1000,
    osc.velocity = 0.1;
    model.mats.push_back(osc);
    model.probes = {{"x", ProbeKind::Position, "osc"}};
    model.controls.push_back(std::move(control));
    validate_model(model);
    return model;
}

TEST(Controls, AnEnvelopeRetunesAnOscillatorWhileItRuns) {
    Control c;
    c.id = "tune", c.rate = "audio", c.target = {"osc", "stiffness"};
    c.source = Control::Source::Envelope;
    c.envelope = {{0.0, 1000.0}, {1.0, 1000.0}, {1.0001, 4000.0}};
    c.minimum = 500, c.maximum = 8000;
    Simulation sim(compile(oscillator_with_control(c)));
    std::vector<double> before, after;
    for (int i = 0; i < 2 * 48000; ++i) {
        sim.step();
        (i < 48000 ? before : after).push_back(sim.probe(0));
    }
    after.erase(after.begin(), after.begin() + 100);
    EXPECT_NEAR(test::zero_crossing_frequency(before, kFs) / discrete_frequency(1000), 1.0, 1e-5);
    EXPECT_NEAR(test::zero_crossing_frequency(after, kFs) / discrete_frequency(4000), 1.0, 1e-5);
}

TEST(Controls, AGestureAxisDrivesAParameterWithinItsRange) {
    Control c;
    c.id = "hand", c.rate = "audio", c.target = {"osc", "stiffness"};
    c.source = Control::Source::Gesture;
    c.axis = GestureAxis::Press;
    c.offset = 1000, c.gain = 1e6;  // N/m per metre of the pressure axis
    c.minimum = 1000, c.maximum = 3000;
    Simulation sim(compile(oscillator_with_control(c)));
    const auto slot = sim.model().resolve_parameter({"osc", "stiffness"});
    const Gesture g("press", {{0, 0, 0}, {1, 0, 0.001}, {2, 0, 0.01}});
    sim.set_gesture_track(&g);
    auto stiffness = [&] {
        const auto& lv = sim.model().levels[slot.level];
        return lv.ground_k[lv.grounds[slot.index].index];
    };
    for (int i = 0; i < 24000; ++i) sim.step();
    // The last control update read the gesture at the start of step 23999.
    EXPECT_NEAR(stiffness(), 1000 + 1e6 * 0.001 * 23999 / 48000, 1e-6);
    for (int i = 0; i < 72000; ++i) sim.step();
    EXPECT_EQ(stiffness(), 3000) << "clamped to the range";
}

TEST(Controls, RefusesARangeThatWouldMakeTheModelUnstable) {
    Control c;
    c.id = "too_far", c.rate = "audio", c.target = {"osc", "stiffness"};
    c.source = Control::Source::Envelope;
    c.envelope = {{0.0, 1000.0}};
    c.minimum = 1000, c.maximum = 4.0 * kMass / (kDt * kDt) * 1.01;  // past K·T²/m = 4
    Model model;
    Mat osc;
    osc.id = "osc", osc.kind = MatKind::Oscillator, osc.mass = kMass, osc.stiffness = 1000;
    model.mats.push_back(osc);
    model.controls.push_back(c);
    try {
        validate_model(model);
        FAIL() << "accepted an unstable range";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("when control \"too_far\""), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("unstable"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace archet
