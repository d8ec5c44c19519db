// Energy: the undamped scheme conserves its discrete energy exactly, and with damping and a
// moving hand the books balance: stored change = hand work − dissipation, step by step.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "archet/builders/bowed_string.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/compiled_model.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

TEST(Energy, UndampedChainConservesDiscreteEnergyOverAMillionSteps) {
    const double fs = 48000, dt = 1 / fs, m = 1e-4;
    Model model = test::chain(24, m, 0.8 * m / (dt * dt), 0.0, fs);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> u(-1e-3, 1e-3);
    for (auto& mat : model.mats)
        if (mat.kind == MatKind::Mass) mat.position = u(random), mat.velocity = 100 * u(random);
    validate_model(model);
    Simulation sim(compile(model));
    sim.step();
    const double e0 = sim.stored_energy();
    ASSERT_GT(e0, 0);
    double worst = 0;
    for (int i = 0; i < 1'000'000; ++i) {
        sim.step();
        if (i % 997 == 0) worst = std::max(worst, std::abs(sim.stored_energy() - e0) / e0);
    }
    worst = std::max(worst, std::abs(sim.stored_energy() - e0) / e0);
    EXPECT_LT(worst, 1e-11) << "drift means an ordering or sign bug in the scheme";
}

TEST(Energy, NaiveEnergyWithSquaredSpringTermIsNotConserved) {
    // Guards the test above: the cross-product spring term is what makes it exact.
    const double fs = 48000, dt = 1 / fs, m = 1e-4;
    Model model = test::chain(3, m, 0.8 * m / (dt * dt), 0.0, fs);
    model.mats[1].position = 1e-3;
    Simulation sim(compile(model));
    auto naive = [&] {
        double e = 0;
        const auto& lv = sim.model().levels[0];
        for (int s = 1; s <= lv.size; ++s) {
            const double v = (lv.x()[s] - lv.x_prev()[s]) / lv.dt;
            e += 0.5 * lv.mass[s] * v * v;
        }
        for (int j = 1; j < lv.size; ++j) {
            const double d = lv.x()[j] - lv.x()[j + 1];
            e += 0.5 * lv.chain_k[j] * d * d;
        }
        return e;
    };
    sim.step();
    const double e0 = naive();
    double spread = 0;
    for (int i = 0; i < 1000; ++i)
        sim.step(), spread = std::max(spread, std::abs(naive() - e0) / e0);
    EXPECT_GT(spread, 1e-3);
}

TEST(Energy, BooksBalanceStepByStepWithDampingFrictionAndHand) {
    BowedStringOptions options;
    options.pitch = 220;
    options.haptic_divider = 1;  // one rate level: the exact per-step identity holds
    Model model = build_bowed_string(options);
    Simulation sim(compile(model));
    sim.enable_accounting(true);
    double previous = sim.stored_energy();
    double dissipated_before = 0, work_before = 0;
    double worst = 0, scale = 0;
    for (int i = 0; i < 48000; ++i) {
        sim.step();
        double dissipated = 0;
        for (double d : sim.dissipated_by_element()) dissipated += d;
        const double stored = sim.stored_energy();
        const double balance = (stored - previous) -
                               ((sim.hand_work() - work_before) - (dissipated - dissipated_before));
        // The pressure buffer's contact switching is the only non-conservative term left out.
        const auto& bow = sim.model().bows[0];
        if (bow.normal > 0 && i > 2000) worst = std::max(worst, std::abs(balance));
        scale = std::max(scale, stored);
        previous = stored, dissipated_before = dissipated, work_before = sim.hand_work();
    }
    ASSERT_GT(scale, 0);
    EXPECT_LT(worst, 1e-9 * scale);
}

TEST(Energy, MultiRateBowingNeverAddsEnergyOverAnyHapticPeriod) {
    // Across rate levels the coupling holds and averages forces; over every haptic period
    // the stored energy may grow only by what the hand put in.
    BowedStringOptions options;
    options.pitch = 220;
    Model model = build_bowed_string(options);
    Simulation sim(compile(model));
    const int divider = options.haptic_divider;
    for (int i = 0; i < divider; ++i) sim.step();
    double stored = sim.stored_energy(), work = sim.hand_work(), worst = -1, scale = 0;
    for (int period = 0; period < 3 * 48000 / divider; ++period) {
        for (int i = 0; i < divider; ++i) sim.step();
        const double gain = (sim.stored_energy() - stored) - (sim.hand_work() - work);
        worst = std::max(worst, gain);
        stored = sim.stored_energy(), work = sim.hand_work();
        scale = std::max(scale, stored);
    }
    EXPECT_LE(worst, 1e-12 * scale);
}

}  // namespace
}  // namespace archet
