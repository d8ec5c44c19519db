// Crossing rate levels: a slow link's force is held over its period on fast MATs and a fast
// link's forces are averaged over a slow MAT's period, so impulse is conserved exactly; the
// coupling is stable and adds no energy.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "archet/common/input_error.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/compiled_model.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

constexpr int kDivider = 16;

Model two_rate_pair(const std::string& link_rate) {
    Model model;
    model.rates = {{"audio", 1}, {"haptic", kDivider}};
    model.mats = {test::mass("fast", 0.02, 0.0, "audio"),
                  test::mass("slow", 0.05, 0.003, "haptic")};
    model.mats[0].velocity = 0.3;
    model.mats[1].velocity = -0.1;
    model.lias = {
        test::spring_damper("link", "fast", "slow", 2000, 0.5, link_rate)};  // above K·T/2
    model.probes = {{"f_slow", ProbeKind::Force, "slow"}, {"f_fast", ProbeKind::Force, "fast"}};
    validate_model(model);
    return model;
}

class ImpulseAcrossRates : public ::testing::TestWithParam<std::string> {};

TEST_P(ImpulseAcrossRates, MomentumIsConservedAtEverySlowPeriod) {
    Simulation sim(compile(two_rate_pair(GetParam())));
    const auto fast = sim.model().mat_slots.at("fast"), slow = sim.model().mat_slots.at("slow");
    const double p0 = 0.02 * 0.3 + 0.05 * -0.1;
    // A slow link's period ends before its next tick; a slow MAT's averaging window ends on
    // its tick, one step later.
    if (GetParam() == "audio") sim.step();
    double worst = 0, rounding = 0;
    const int periods = 3000;
    for (int period = 0; period < periods; ++period) {
        for (int i = 0; i < kDivider; ++i) sim.step();
        worst =
            std::max(worst, std::abs(0.02 * sim.velocity(fast) + 0.05 * sim.velocity(slow) - p0));
        // Velocities are differences of positions: their rounding grows with the positions.
        const double eps = std::numeric_limits<double>::epsilon();
        // and accumulate as a random walk over the steps taken.
        const double steps = (period + 1.0) * kDivider;
        rounding = std::max(rounding, 8 * eps * std::sqrt(steps) *
                                          (0.02 * std::abs(sim.position(fast)) * 48000 +
                                           0.05 * std::abs(sim.position(slow)) * 48000 / kDivider));
    }
    EXPECT_LT(worst, rounding);
    // Something did happen: the link exchanged momentum.
    EXPECT_GT(std::abs(sim.velocity(slow) + 0.1), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(LinkRate, ImpulseAcrossRates, ::testing::Values("haptic", "audio"));

TEST(MultiRate, ASlowMatReadsTheMeanOfTheFastForces) {
    Simulation sim(compile(two_rate_pair("audio")));
    sim.step();  // the slow MAT's window: the fast steps after one slow tick up to the next
    double sum = 0;
    for (int period = 0; period < 50; ++period) {
        sum = 0;
        for (int i = 0; i < kDivider; ++i) {
            sim.step();
            sum += sim.probe(1);  // force on the fast mass this fast step
        }
        // The slow mass integrates the mean; its force readback is that mean (opposite sign).
        EXPECT_NEAR(sim.probe(0), -sum / kDivider, 1e-12 * std::abs(sum) + 1e-15);
    }
}

constexpr double kHoldStiffness = 500, kSlowPeriod = kDivider / 48000.0;

Model hung_pair(double hold_damping) {
    // A fast pair hung from a slow anchor by a slow spring-damper; no other damping.
    Model model;
    model.rates = {{"audio", 1}, {"haptic", kDivider}};
    model.mats = {test::fixed("anchor", 0.0, "haptic"), test::mass("a", 0.01, 0.002),
                  test::mass("b", 0.01, -0.001)};
    model.lias = {
        test::spring_damper("hold", "anchor", "a", kHoldStiffness, hold_damping, "haptic"),
        test::spring_damper("ab", "a", "b", 3000, 0.0, "audio")};
    return model;
}

double energy_ratio_after(Model model, double seconds) {
    Simulation sim(compile(model));
    for (int i = 0; i < kDivider; ++i) sim.step();
    const double start = sim.stored_energy();
    for (int i = 0; i < seconds * 48000; ++i) sim.step();
    return sim.stored_energy() / start;
}

TEST(MultiRate, AHeldSpringWithoutEnoughDampingIsRefusedBecauseItGainsEnergy) {
    // Below Colgate's bound Z = K·T/2 the zero-order hold feeds energy in.
    const Model weak = hung_pair(0.5 * kHoldStiffness * kSlowPeriod / 2);
    try {
        validate_model(weak);
        FAIL() << "accepted an active coupling";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("link \"hold\": crosses rate levels"),
                  std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("K·T/2"), std::string::npos) << e.what();
    }
    EXPECT_GT(energy_ratio_after(weak, 5.0), 10.0) << "why the rule exists";
}

TEST(MultiRate, AHeldSpringAboveTheBoundOnlyLosesEnergy) {
    const Model model = hung_pair(1.2 * kHoldStiffness * kSlowPeriod / 2);
    validate_model(model);
    Simulation sim(compile(model));
    for (int i = 0; i < kDivider; ++i) sim.step();
    double previous = sim.stored_energy();
    const double start = previous;
    for (int window = 0; window < 20; ++window) {
        for (int i = 0; i < 24000; ++i) sim.step();
        EXPECT_LT(sim.stored_energy(), previous) << "window " << window;
        previous = sim.stored_energy();
    }
    EXPECT_LT(previous, 1e-3 * start);
}

// A hand at the haptic rate holding a bow mass through a spring-damper; the link runs at
// `link_rate`, the hand at `hand_rate`.
Model hand_and_bow(const std::string& hand_rate, const std::string& link_rate, double damping) {
    Model model;
    model.rates = {{"audio", 1}, {"haptic", kDivider}};
    Mat hand;
    hand.id = "hand", hand.kind = MatKind::Gesture, hand.rate = hand_rate;
    hand.axis = GestureAxis::Slide;
    model.mats = {hand, test::mass("bow", 0.05, 0.0, "audio")};
    model.lias = {test::spring_damper("hold", "hand", "bow", 1000, damping, link_rate)};
    // A slow stroke, a quick one, then back.
    model.gesture = Gesture(
        "stroke", {{0.0, 0.0, 0.0}, {0.2, 0.01, 0.0}, {0.25, 0.03, 0.0}, {0.5, -0.01, 0.0}});
    return model;
}

TEST(MultiRate, AFasterLinkFollowsAHandAlongItsTrackWithoutDelay) {
    // The hand's points tick at 3 kHz; the link at the bow's rate sees the hand along a line
    // between its ticks, so the bow moves as if the hand were read at every step.
    Simulation haptic(compile(hand_and_bow("haptic", "audio", 10)));
    Simulation audio(compile(hand_and_bow("audio", "audio", 10)));
    const auto bow = haptic.model().mat_slots.at("bow");
    const auto reference = audio.model().mat_slots.at("bow");
    double worst = 0, largest = 0;
    for (int n = 0; n < 24000; ++n) {
        haptic.step(), audio.step();
        worst = std::max(worst, std::abs(haptic.position(bow) - audio.position(reference)));
        largest = std::max(largest, std::abs(audio.position(reference)));
    }
    EXPECT_GT(largest, 0.02) << "the bow followed the stroke";
    EXPECT_LT(worst, 1e-9 * largest);
}

TEST(MultiRate, AHandLinkAtTheBowsRateNeedsNoColgateDamping) {
    // The hand's steps are booked as the hand's work at the link's rate: the link is as
    // passive as at one rate, undamped or not. The same spring at the hand's rate would hold
    // its force and is refused without damping.
    EXPECT_NO_THROW(validate_model(hand_and_bow("haptic", "audio", 0.0)));
    EXPECT_THROW(validate_model(hand_and_bow("haptic", "haptic", 0.0)), InputError);
    Simulation sim(compile(hand_and_bow("haptic", "audio", 0.0)));
    double lowest = sim.stored_energy() - sim.hand_work(), worst = 0, scale = 0;
    for (int n = 0; n < 24000; ++n) {
        sim.step();
        const double balance = sim.stored_energy() - sim.hand_work();
        worst = std::max(worst, balance - lowest);
        lowest = std::min(lowest, balance);
        scale = std::max(scale, sim.stored_energy());
    }
    EXPECT_GT(scale, 1e-3) << "the hand moved the bow";
    EXPECT_LT(worst, 1e-11 * scale) << "energy came from nowhere";
}

}  // namespace
}  // namespace archet
