// The gesture link with a simulated hand on the device: whatever the hand does (sine, chirp,
// random, impact), over every window, down to one step, the model gains no more energy than
// the hand put in; forces stay within what the device renders; stale data and a stalled simulation
// give zero force within one period.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <numbers>
#include <random>
#include <thread>
#include <vector>

#include "archet/evdev_device.hpp"
#include "archet/files/model_file.hpp"
#include "archet/haptic_choice.hpp"
#include "archet/haptic_link.hpp"
#include "archet/haptic_loop.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/simulated_hand.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

using Target = std::function<GestureSample(double)>;

struct Outcome {
    /// max over every window [i, j] of ΔE − W_hand (J): the rise of E − W above its lowest
    /// value so far, checked after every step.
    double worst_gain = -1;
    double energy_scale = 0;
    double max_force = 0;
    std::uint64_t ticks = 0, stale = 0;
    double max_friction = 0;
};

// The engine's loop in lockstep: hand and model advance on one clock.
Outcome play(const Target& target, double seconds, SimulatedHandOptions hand_options = {}) {
    Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    model.gesture.reset();
    Simulation sim(compile(model));
    SimulatedHand hand(hand_options);
    HapticLink link(hand);
    const double fs = sim.sample_rate(), dt = 1 / fs;
    const int divider = 16;
    Outcome run;
    // E − W never rising over any window is the same as it never rising above its value at
    // any earlier step: keep the lowest value seen and compare every step with it.
    double lowest = sim.stored_energy() - sim.hand_work();
    for (std::uint64_t n = 0; n < static_cast<std::uint64_t>(seconds * fs); ++n) {
        const double t = static_cast<double>(n) * dt;
        hand.set_target(target(t));
        hand.advance(t, dt);
        if (n % divider == 0) {
            link.tick(sim, t, divider * dt);
            run.max_force = std::max({run.max_force, std::abs(link.last_force().slide),
                                      std::abs(link.last_force().press)});
        }
        sim.step();
        const double stored = sim.stored_energy(), balance = stored - sim.hand_work();
        run.worst_gain = std::max(run.worst_gain, balance - lowest);
        lowest = std::min(lowest, balance);
        run.energy_scale = std::max(run.energy_scale, stored);
        run.max_friction = std::max(run.max_friction, std::abs(sim.model().bows[0].friction));
    }
    run.ticks = link.ticks(), run.stale = link.stale_ticks();
    return run;
}

void expect_passive(const Outcome& r, const char* what) {
    EXPECT_GT(r.max_friction, 0.01) << what << ": the hand bowed the string";
    // Over every window, down to a single step, the model holds no more energy than the
    // hand put in.
    EXPECT_LE(r.worst_gain, 1e-12 * r.energy_scale) << what << ": the coupling created energy";
    EXPECT_LE(r.stale, 4u) << what << ": only before the device's first reading";
}

GestureSample pressing(double slide) {
    return {slide, 0.0015};
}

TEST(Haptics, PassiveUnderSine) {
    expect_passive(
        play([](double t) { return pressing(0.03 * std::sin(2 * std::numbers::pi * 1.5 * t)); },
             2.0),
        "sine");
}

TEST(Haptics, PassiveUnderChirp) {
    expect_passive(play(
                       [](double t) {
                           return pressing(0.02 * std::sin(2 * std::numbers::pi * (1 + 4 * t) * t));
                       },
                       2.0),
                   "chirp");
}

TEST(Haptics, PassiveUnderRandomMotion) {
    std::mt19937 random(3);
    std::uniform_real_distribution<double> u(-0.04, 0.04), p(0.0, 0.004);
    std::vector<GestureSample> points;
    for (int i = 0; i < 60; ++i) points.push_back({u(random), p(random)});
    expect_passive(
        play([&](double t) { return points[static_cast<std::size_t>(t * 25) % points.size()]; },
             2.0),
        "random");
}

TEST(Haptics, PassiveUnderAnImpact) {
    // A steady stroke, then the hand slams the bow down.
    expect_passive(play(
                       [](double t) {
                           return GestureSample{0.05 * t, t < 0.7 ? 0.001 : 0.02};
                       },
                       1.5),
                   "impact");
}

TEST(Haptics, ForcesStayWithinWhatTheDeviceRenders) {
    SimulatedHandOptions weak;
    weak.capabilities.max_force = 0.05;  // a small device: the bow force exceeds it
    const Outcome r = play([](double t) { return GestureSample{0.05 * t, 0.004}; }, 1.0, weak);
    EXPECT_LE(r.max_force, 0.05);
    EXPECT_GT(r.max_force, 0.049);
}

TEST(Haptics, StaleDeviceDataGivesZeroForce) {
    // A device whose readings stopped: the link holds position and renders nothing.
    class FrozenDevice final : public HapticDevice {
      public:
        HapticCapabilities capabilities() const override { return {}; }
        HapticReading read() const override {
            return {0.01, 0.003, 0.0};
        }  // measured at t = 0, never again
        void write(double s, double p, double) override { last = {s, p}; }
        GestureSample last{1, 1};
    } device;
    Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    model.gesture.reset();
    Simulation sim(compile(model));
    HapticLink link(device);
    link.tick(sim, 0.0, 1.0 / 3000);
    EXPECT_EQ(link.stale_ticks(), 0u);
    link.tick(sim, 0.02, 1.0 / 3000);  // 20 ms later, no new reading
    EXPECT_EQ(link.stale_ticks(), 1u);
    EXPECT_EQ(device.last.slide, 0.0);
    EXPECT_EQ(device.last.press, 0.0);
}

TEST(Haptics, DeviceLetsGoWhenTheSimulationStalls) {
    SimulatedHand hand;
    hand.write(2.0, 1.0, 0.0);
    for (double t = 0; t < 0.0025; t += 1.0 / 48000) hand.advance(t, 1.0 / 48000);
    // The force arrived after the latency and was rendered...
    SimulatedHand fresh;
    fresh.write(2.0, 1.0, 0.0);
    double rendered = 0;
    for (double t = 0; t < 0.0019; t += 1.0 / 48000) {
        fresh.advance(t, 1.0 / 48000);
        rendered = std::max(rendered, fresh.applied_force().slide);
        fresh.write(2.0, 1.0, t);  // the simulation keeps sending
    }
    EXPECT_EQ(rendered, 2.0);
    // ...and with no new force for one device period, it is gone.
    EXPECT_EQ(hand.applied_force().slide, 0.0);
    EXPECT_EQ(hand.applied_force().press, 0.0);
}

TEST(Haptics, HandReadingsRespectRateLatencyAndResolution) {
    SimulatedHandOptions o;
    o.capabilities.position_rate = 500;
    o.latency = 0.004;
    o.resolution = 1e-3;
    SimulatedHand hand(o);
    hand.set_target({0.02, 0.0});
    double previous_time = -1;
    int updates = 0;
    for (int n = 0; n < 48000; ++n) {
        const double t = n / 48000.0;
        hand.advance(t, 1 / 48000.0);
        const HapticReading r = hand.read();
        if (r.time != previous_time && r.time >= 0) {
            ++updates;
            EXPECT_NEAR(std::remainder(r.slide, 1e-3), 0.0, 1e-12) << "quantised to the resolution";
            EXPECT_GE(t - r.time, 0.004 - 1e-9) << "reported after the latency";
            previous_time = r.time;
        }
    }
    EXPECT_NEAR(updates, 500, 3) << "at the device's own rate";
    EXPECT_NEAR(hand.position().slide, 0.02, 1e-3) << "the hand reached its target";
}

TEST(Haptics, AForceFeedbackJoystickAnswersThroughEvdev) {
    const auto devices = list_evdev_devices();
    if (devices.empty())
        GTEST_SKIP() << "no force-feedback joystick in /dev/input (needs hardware)";
    EXPECT_EQ(devices.front().id(), "evdev:" + devices.front().address);
    EvdevDevice device(devices.front().address);
    EXPECT_FALSE(device.capabilities().name.empty());
    device.write(0.1, 0.0, 0.0);  // a gentle push, then let go
    bool answered = false;        // waited for, up to a generous minute: not assumed after 50 ms
    for (int i = 0; i < 12000 && !(answered = !device.stale(0.0, 0.02)); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    EXPECT_TRUE(answered) << "its I/O thread answers";
    const HapticReading r = device.read();
    EXPECT_LE(std::abs(r.slide), device.capabilities().range);
}

// `archet devices` and the studio's settings list the same choices, each under the id
// --haptic takes: the simulated hand always, last, after whatever joysticks are plugged in.
TEST(Haptics, EveryListedChoiceCarriesTheIdThatOpensIt) {
    const auto choices = list_haptic_choices();
    ASSERT_FALSE(choices.empty());
    const HapticDeviceInfo& sim = choices.back();
    EXPECT_EQ(sim.backend, "sim");
    EXPECT_EQ(describe(sim), "sim: simulated hand (always available)");
    const HapticChoice opened = open_haptic_device(sim.id());
    EXPECT_NE(opened.hand, nullptr) << "\"" << sim.id() << "\" opens the simulated hand";
    for (const HapticDeviceInfo& d : choices) {
        if (d.backend == "sim") continue;
        EXPECT_EQ(d.id(), d.backend + ":" + d.address);
        EXPECT_EQ(describe(d).rfind(d.backend + " " + d.address + ": " + d.name, 0), 0u)
            << describe(d);
        EXPECT_GE(d.axes, 2) << d.id();
    }
    const HapticDeviceInfo joystick{"sdl", "3", "Pad", 2, false};
    EXPECT_EQ(describe(joystick), "sdl 3: Pad (positions only)");
    EXPECT_EQ(joystick.id(), "sdl:3");
    const HapticDeviceInfo evdev{"evdev", "/dev/input/event7", "Wheel", 3, true};
    EXPECT_EQ(describe(evdev), "evdev /dev/input/event7: Wheel (force feedback)");
    EXPECT_EQ(evdev.id(), "evdev:/dev/input/event7");
}

// The engine swaps models under a device that goes on: the hand's clock is the device's, not
// the model's (a new model's time starts again at 0). Judged on model time, the simulated hand
// would not report a new position until the new model's time caught up with the old one's.
TEST(Haptics, TheSimulatedHandGoesOnReportingAcrossAModelSwap) {
    Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    model.gesture.reset();
    SimulatedHand hand;
    const auto moving = [](double t) { return GestureSample{-0.05 + 0.1 * t, 0.0015}; };
    double device_time = 0;
    auto play = [&](Simulation& sim, HapticLoop& loop, double seconds) {
        for (int n = 0; n < static_cast<int>(seconds * sim.sample_rate()); ++n) {
            loop.before_step(sim, moving(device_time), device_time);
            sim.step();
            device_time += 1.0 / sim.sample_rate();
        }
    };
    Simulation first(compile(model));
    HapticLoop first_loop(hand, &hand, first);
    play(first, first_loop, 1.0);
    Simulation second(compile(model));  // the swap: a new model, at rest, at its time 0
    HapticLoop second_loop(hand, &hand, second);
    const double before = hand.read().slide;
    play(second, second_loop, 0.1);
    EXPECT_NEAR(hand.read().slide - before, 0.1 * 0.1, 0.002) << "the hand goes on moving";
    EXPECT_NEAR(second.device_position().slide, hand.read().slide, 1e-9)
        << "and the new model's gesture points follow it";
    EXPECT_GT(std::abs(second.model().bows[0].friction), 0.01) << "the new model is bowed";
}

// The engine and `play` run a bowed string in runs up to the haptic link's next tick
// (Simulation::run()), and move a simulated hand on for the run's other ticks after it
// (HapticLoop::between_link_ticks()). That is the same as a hand moved before every step: the
// same sound, to the byte, and the hand where it would have been, after every run.
TEST(Haptics, AHandMovedOnAfterARunIsWhereItIsMovedTickByTick) {
    Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    model.gesture.reset();
    const auto moving = [](double t) {
        return GestureSample{-0.05 + 0.1 * t + 0.01 * std::sin(31.0 * t), 0.0015};
    };
    SimulatedHand tick_hand, run_hand;
    Simulation by_tick(compile(model)), in_runs(compile(model));
    HapticLoop by_tick_loop(tick_hand, &tick_hand, by_tick),
        in_runs_loop(run_hand, &run_hand, in_runs);
    const double dt = 1.0 / in_runs.sample_rate();
    std::vector<double> sound(64);
    int runs_longer_than_a_tick = 0;
    while (in_runs.tick() < static_cast<std::uint64_t>(0.5 * in_runs.sample_rate())) {
        in_runs_loop.before_step(in_runs, moving(in_runs.time()), in_runs.time());
        const std::uint64_t first = in_runs.tick();
        const std::size_t length =
            std::min<std::uint64_t>(sound.size(), in_runs_loop.ticks_to_link_tick(first));
        ASSERT_EQ(in_runs.run({sound.data(), length}), length);
        for (std::size_t k = 1; k < length; ++k) {
            const double t = static_cast<double>(first + k) / in_runs.sample_rate();
            in_runs_loop.between_link_ticks(moving(t), t, dt);
        }
        runs_longer_than_a_tick += length > 1;
        for (std::size_t k = 0; k < length; ++k) {
            by_tick_loop.before_step(by_tick, moving(by_tick.time()), by_tick.time());
            by_tick.step();
            const double expected = by_tick.output();
            ASSERT_EQ(std::memcmp(&sound[k], &expected, sizeof expected), 0)
                << "tick " << by_tick.tick();
        }
        const HapticReading read = run_hand.read(), read_by_tick = tick_hand.read();
        const GestureSample at = run_hand.position(), at_by_tick = tick_hand.position();
        ASSERT_EQ(std::memcmp(&read, &read_by_tick, sizeof read), 0)
            << "what the hand reports after tick " << in_runs.tick();
        ASSERT_EQ(std::memcmp(&at, &at_by_tick, sizeof at), 0)
            << "where the hand is after tick " << in_runs.tick();
    }
    EXPECT_GT(runs_longer_than_a_tick, 1000) << "it ran in runs";
    EXPECT_EQ(in_runs.bowed_chain_misfit(), "") << "in the bowed string's own loop";
    EXPECT_GT(std::abs(in_runs.model().bows[0].friction), 0.01) << "the hand bowed the string";
}

}  // namespace
}  // namespace archet
