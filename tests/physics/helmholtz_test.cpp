// Every shipped string, full-bandwidth or the paper's, falls into Helmholtz motion with the
// stroke it carries: one slip per period at the period of its first mode, the string moving
// with the bow while sticking; the paper's strings slip for about β of the period and fly back
// at about −v_b(1−β)/β (physics.md §4).

#include <gtest/gtest.h>

#include <cmath>

#include "archet/analysis/bowing_analysis.hpp"
#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/playability.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/builders/stroke_in_band.hpp"
#include "archet/files/model_file.hpp"
#include "archet/physics/compiled_model.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

struct Bowing {
    std::vector<double> slip, string_velocity, bow_velocity;
    double beta = 0, pitch = 0, fs = 0;
};

std::size_t probe_index(const Model& m, const std::string& id) {
    for (std::size_t i = 0; i < m.probes.size(); ++i)
        if (m.probes[i].id == id) return i;
    throw std::runtime_error("no probe " + id);
}

Bowing bow(const Model& model, double seconds, const Gesture* gesture = nullptr) {
    Bowing b;
    Simulation sim(compile(model));
    if (gesture) sim.set_gesture_track(gesture);
    b.fs = sim.sample_rate();
    b.pitch = analyse_modes(model).fundamental;
    b.beta = bow_position(model);
    const auto slip = probe_index(model, "slip_v"), sv = probe_index(model, "bow_point_v"),
               bv = probe_index(model, "bow_v");
    for (int i = 0; i < seconds * b.fs; ++i) {
        sim.step();
        b.slip.push_back(sim.probe(slip));
        b.string_velocity.push_back(sim.probe(sv));
        b.bow_velocity.push_back(sim.probe(bv));
    }
    return b;
}

// Steady Helmholtz motion from 1.5 s to the stroke's lift at 2.6 s.
void expect_helmholtz(const Bowing& b, const std::string& what) {
    const auto a = analyse_bowing(b.slip, b.fs, b.pitch, static_cast<std::size_t>(1.5 * b.fs),
                                  static_cast<std::size_t>(2.55 * b.fs));
    EXPECT_TRUE(a.helmholtz()) << what << ": " << a.slips_per_period << " slips per period, "
                               << a.pitch_cents << " cents, spread " << a.period_spread;
    // String velocity at the bow: the bow's while sticking.
    double stick_sum = 0;
    int stick_count = 0;
    for (std::size_t i = static_cast<std::size_t>(1.5 * b.fs);
         i < static_cast<std::size_t>(2.55 * b.fs); ++i)
        if (b.slip[i] == 0.0) stick_sum += b.string_velocity[i] - b.bow_velocity[i], ++stick_count;
    ASSERT_GT(stick_count, 0) << what;
    EXPECT_NEAR(stick_sum / stick_count, 0.0, 1e-12) << what;
}

class ShippedString : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedString, PlaysHelmholtzMotionWithItsOwnStroke) {
    const Model model = load_model_file(test::resource("models/" + GetParam() + ".json"));
    ASSERT_TRUE(model.gesture) << "every shipped string carries the stroke that plays it";
    const Bowing b = bow(model, 2.6);
    expect_helmholtz(b, GetParam());
    const double pitch = std::stod(GetParam().substr(std::string("bowed-string-").size()));
    EXPECT_NEAR(1200 * std::log2(b.pitch / pitch), 0.0, 1.0) << "tuned to its pitch";
}

TEST_P(ShippedString, PlaysTheShippedSteadyBowWhereThatIsInItsBand) {
    const Model model = load_model_file(test::resource("models/" + GetParam() + ".json"));
    const Gesture steady = load_gesture_file(test::resource("gestures/steady-bow.json"));
    const HelmholtzBand band = helmholtz_band(model, 0.1);
    const double force = force_for_press(model, 0.0015);  // the shipped stroke's press
    // The band is known at the forces played: inside it means its middle third (in log force),
    // away from edges that the sampling only brackets.
    const double third = std::cbrt(band.high / band.low);
    if (force < band.low * third || force > band.high / third)
        GTEST_SKIP() << GetParam() << ": the shipped stroke's " << force
                     << " N is not inside its band " << band.low << "–" << band.high << " N";
    expect_helmholtz(bow(model, 2.6, &steady), GetParam() + " with steady-bow.json");
}

INSTANTIATE_TEST_SUITE_P(
    Shipped, ShippedString,
    ::testing::Values("bowed-string-110", "bowed-string-220", "bowed-string-440",
                      "bowed-string-880", "bowed-string-110-harmonic", "bowed-string-220-harmonic",
                      "bowed-string-440-harmonic", "bowed-string-880-harmonic",
                      "bowed-string-110-paper", "bowed-string-220-paper", "bowed-string-440-paper",
                      "bowed-string-880-paper", "bowed-string-110-harmonic-paper",
                      "bowed-string-220-harmonic-paper", "bowed-string-440-harmonic-paper",
                      "bowed-string-880-harmonic-paper"),
    [](const auto& info) {
        std::string name = info.param;
        for (char& c : name)
            if (c == '-') c = '_';
        return name;
    });

// The paper's strings keep the paper's signature: the slip lasts about β of the period and
// the string flies back at about −v_b(1−β)/β.
TEST(Helmholtz, ThePapersStringSlipsForAboutBetaOfThePeriod) {
    const Model model = load_model_file(test::resource("models/bowed-string-220-paper.json"));
    const Gesture steady = load_gesture_file(test::resource("gestures/steady-bow.json"));
    const Bowing b = bow(model, 2.6, &steady);
    const auto a = analyse_bowing(b.slip, b.fs, b.pitch, static_cast<std::size_t>(1.5 * b.fs),
                                  static_cast<std::size_t>(2.55 * b.fs));
    EXPECT_TRUE(a.helmholtz());
    EXPECT_GT(a.slip_share, 0.8 * b.beta);
    EXPECT_LT(a.slip_share, 2.0 * b.beta);
    double slip_min = 0;
    for (std::size_t i = static_cast<std::size_t>(1.5 * b.fs);
         i < static_cast<std::size_t>(2.55 * b.fs); ++i)
        slip_min = std::min(slip_min, b.string_velocity[i]);
    EXPECT_NEAR(slip_min / (-0.1 * (1 - b.beta) / b.beta), 1.0, 0.3);
}

TEST(Helmholtz, SlipShareGrowsWithBowDistanceFromTheBridge) {
    const Gesture steady = load_gesture_file(test::resource("gestures/steady-bow.json"));
    double previous = 0;
    for (double beta : {0.1, 0.15, 0.2, 0.25}) {
        BowedStringOptions o;
        o.pitch = 220, o.bow_position = beta, o.paper = true;
        const Bowing b = bow(build_bowed_string(o), 2.0, &steady);
        const auto a = analyse_bowing(b.slip, b.fs, b.pitch, static_cast<std::size_t>(1.0 * b.fs),
                                      static_cast<std::size_t>(1.9 * b.fs));
        EXPECT_TRUE(a.helmholtz())
            << "beta " << beta << ": " << a.slips_per_period << " slips per period";
        EXPECT_GT(a.slip_share, previous) << "beta " << beta;
        previous = a.slip_share;
    }
}

TEST(Helmholtz, TooLittleForceGivesSeveralSlipsPerPeriod) {
    // Below Schelleng's minimum bow force the string slips more than once per period.
    Model model = load_model_file(test::resource("models/bowed-string-110-paper.json"));
    model.find_mat("hand_press")->position_scale = 0.3;
    const Gesture steady = load_gesture_file(test::resource("gestures/steady-bow.json"));
    const Bowing b = bow(model, 2.0, &steady);
    const auto a = analyse_bowing(b.slip, b.fs, b.pitch, static_cast<std::size_t>(1.0 * b.fs),
                                  static_cast<std::size_t>(1.9 * b.fs));
    EXPECT_GT(a.slips_per_period, 1.5);
    EXPECT_FALSE(a.helmholtz());
}

}  // namespace
}  // namespace archet
