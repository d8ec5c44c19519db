// Model and gesture files: load → save round-trips exactly, the shipped models are what the
// builder makes today, and every field survives.

#include <gtest/gtest.h>

#include "archet/builders/bowed_string.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_validation.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

class ShippedModel : public ::testing::TestWithParam<int> {};

TEST_P(ShippedModel, LoadThenSaveGivesTheSameBytes) {
    const auto path = test::resource("models/bowed-string-" + std::to_string(GetParam()) + ".json");
    const std::string text = test::read_file(path);
    const Model model = parse_model(text, path.string());
    validate_model(model);
    EXPECT_EQ(format_model(model), text);
}

TEST_P(ShippedModel, IsWhatTheBuilderMakesToday) {
    if (test::kUnderSanitizer && GetParam() == 110)
        GTEST_SKIP() << test::kLargeStringUnderSanitizer;
    BowedStringOptions o;
    o.pitch = GetParam();
    EXPECT_EQ(format_model(build_bowed_string(o)),
              test::read_file(
                  test::resource("models/bowed-string-" + std::to_string(GetParam()) + ".json")))
        << "regenerate with: archet new bowed-string --pitch " << GetParam();
}

INSTANTIATE_TEST_SUITE_P(PaperPitches, ShippedModel, ::testing::Values(110, 220, 440, 880));

TEST(ModelFile, EveryElementKindAndFieldRoundTrips) {
    Model m;
    m.name = "all kinds";
    m.description = "ünïcode and \"quotes\"";
    m.sample_rate = 44100;
    m.output_gain = 0.25;
    m.rates = {{"audio", 1}, {"haptic", 15}};
    m.mats = {test::mass("a", 1e-3, 0.5e-3), test::fixed("f", -1e-3)};
    Mat osc;
    osc.id = "o", osc.kind = MatKind::Oscillator, osc.mass = 0.1, osc.stiffness = 300,
    osc.damping = 0.01;
    osc.velocity = 0.125, osc.display = {{12.5, -3}};
    Mat hand;
    hand.id = "h", hand.kind = MatKind::Gesture, hand.rate = "haptic",
    hand.axis = GestureAxis::Press;
    hand.position_scale = 2.5, hand.force_scale = 0.5;
    m.mats.push_back(osc);
    m.mats.push_back(hand);
    m.mats.push_back(test::mass("p", 0.01));
    m.mats.push_back(test::fixed("s"));
    m.lias = {test::spring_damper("l1", "a", "o", 100, 0.01)};
    Lia spring, damper, buffer, bow;
    spring.id = "sp", spring.kind = LiaKind::Spring, spring.from = "a", spring.to = "f",
    spring.stiffness = 5, spring.length = 0.001;
    damper.id = "dm", damper.kind = LiaKind::Damper, damper.from = "o", damper.to = "f",
    damper.damping = 0.2;
    buffer.id = "bf", buffer.kind = LiaKind::Buffer, buffer.from = "p", buffer.to = "h",
    buffer.stiffness = 1e3, buffer.damping = 1, buffer.length = 0.002, buffer.rate = "haptic";
    bow.id = "bw", bow.kind = LiaKind::BowFriction, bow.from = "o", bow.to = "a", bow.press = "p",
    bow.surface = "s", bow.stiffness = 1e4, bow.mu_static = 0.7, bow.mu_dynamic = 0.2,
    bow.v0 = 0.05;
    m.lias.insert(m.lias.end(), {spring, damper, buffer, bow});
    Control c;
    c.id = "c", c.target = {"bw", "mu_s"}, c.source = Control::Source::Envelope,
    c.envelope = {{0, 0.7}, {1, 0.9}}, c.minimum = 0.5, c.maximum = 1.0;
    m.controls.push_back(c);
    m.probes = {{"x", ProbeKind::Position, "a"}, {"e", ProbeKind::Energy, ""}};
    m.outputs = {{"o", Output::Signal::Velocity, 0.5}};
    m.gesture = Gesture("g", {{0, 0, 0}, {0.5, 0.01, 0.002}});

    const std::string text = format_model(m);
    const Model back = parse_model(text);
    EXPECT_EQ(format_model(back), text);
    EXPECT_EQ(back.mats.size(), m.mats.size());
    EXPECT_EQ(back.find_mat("h")->position_scale, 2.5);
    EXPECT_EQ(back.find_mat("o")->display->first, 12.5);
    EXPECT_EQ(back.find_lia("bf")->length, 0.002);
    EXPECT_EQ(back.find_lia("bw")->press, "p");
    EXPECT_EQ(back.controls[0].envelope.size(), 2u);
    EXPECT_EQ(*back.gesture, *m.gesture);
    EXPECT_EQ(back.description, m.description);
}

TEST(GestureFile, ShippedGesturesLoadAndRoundTrip) {
    for (const auto* name : {"steady-bow", "crescendo", "detache", "pressure-sweep"}) {
        const Gesture g =
            load_gesture_file(test::resource(std::string("gestures/") + name + ".json"));
        EXPECT_GE(g.keyframes().size(), 3u) << name;
        EXPECT_EQ(parse_gesture(format_gesture(g)), g) << name;
    }
}

TEST(GestureFile, InterpolatesLinearlyAndHoldsOutsideItsRange) {
    const Gesture g("g", {{0.0, 0.0, 0.001}, {1.0, 0.1, 0.003}, {2.0, 0.1, 0.0}});
    EXPECT_DOUBLE_EQ(g.at(0.5).slide, 0.05);
    EXPECT_DOUBLE_EQ(g.at(0.5).press, 0.002);
    EXPECT_DOUBLE_EQ(g.at(1.5).press, 0.0015);
    EXPECT_DOUBLE_EQ(g.at(-1).press, 0.001);
    EXPECT_DOUBLE_EQ(g.at(9).slide, 0.1);
    EXPECT_DOUBLE_EQ(g.at(0.25).slide, 0.025);  // going back in time works too
}

}  // namespace
}  // namespace archet
