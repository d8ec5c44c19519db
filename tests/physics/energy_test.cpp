// Energy: the undamped scheme conserves its discrete energy exactly, and with damping and a
// moving hand the books balance: stored change = hand work − dissipation, step by step.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "archet/builders/bowed_string.hpp"
#include "archet/builders/string_body.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/compiled_model.hpp"
#include "energy_books.hpp"
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

using test::Books;
using test::step_by_step_books;

// The largest growth of stored energy beyond the hand's work over any haptic period.
Books haptic_period_books(Simulation& sim, int divider, int periods) {
    for (int i = 0; i < divider; ++i) sim.step();
    double stored = sim.stored_energy(), work = sim.hand_work();
    Books books{-1, 0};
    for (int period = 0; period < periods; ++period) {
        for (int i = 0; i < divider; ++i) sim.step();
        const double gain = (sim.stored_energy() - stored) - (sim.hand_work() - work);
        books.worst = std::max(books.worst, gain);
        stored = sim.stored_energy(), work = sim.hand_work();
        books.scale = std::max(books.scale, stored);
    }
    return books;
}

TEST(Energy, BooksBalanceStepByStepWithDampingFrictionAndHand) {
    BowedStringOptions options;
    options.pitch = 220;
    options.haptic_divider = 1;  // one rate level: the exact per-step identity holds
    Simulation sim(compile(build_bowed_string(options)));
    const Books books = step_by_step_books(sim, 48000);
    ASSERT_GT(books.scale, 0);
    EXPECT_LT(books.worst, 1e-9 * books.scale);
}

TEST(Energy, MultiRateBowingNeverAddsEnergyOverAnyHapticPeriod) {
    // Across rate levels the coupling holds and averages forces; over every haptic period
    // the stored energy may grow only by what the hand put in.
    BowedStringOptions options;
    options.pitch = 220;
    Simulation sim(compile(build_bowed_string(options)));
    const int divider = options.haptic_divider;
    const Books books = haptic_period_books(sim, divider, 3 * 48000 / divider);
    EXPECT_LE(books.worst, 1e-12 * books.scale);
}

// What the accounts book over `steps` for each chain link and ground, one element at a time.
std::vector<double> chain_and_ground_losses_by_hand(Simulation& sim, int steps) {
    const CompiledLevel& lv = sim.model().levels[0];
    const std::size_t lias = sim.model().source.lias.size();
    std::vector<double> expected(sim.dissipated_by_element().size(), 0.0);
    for (int i = 0; i < steps; ++i) {
        sim.step();
        // After the step x[n+1] is x() and x[n−1] is still in the buffer the next step fills.
        const double* xn = lv.x();
        const double* xp = lv.x_next();
        for (int j = 1; j < lv.size; ++j) {
            if (lv.chain_element[j] < 0) continue;
            const double centred = (xn[j] - xn[j + 1]) - (xp[j] - xp[j + 1]);
            expected[lv.chain_element[j]] += 0.25 * lv.chain_zdt[j] * centred * centred;
        }
        for (const CompiledGround& g : lv.grounds) {
            const int s = g.index;
            expected[lias + g.element] +=
                0.25 * lv.ground_zdt[s] * (xn[s] - xp[s]) * (xn[s] - xp[s]);
        }
    }
    return expected;
}

// The losses of a chain's dampers and of its grounds (a full-bandwidth string's air), booked a
// run of elements at a time, are each element's own, to the bit, whatever order the model
// lists its elements in (out of order, most runs are one element long).
TEST(Energy, EachChainAndGroundDamperIsBookedToItsOwnElement) {
    const Model shipped = load_model_file(test::resource("models/bowed-string-110.json"));
    Model links_reversed = shipped, mats_shuffled = shipped;
    std::reverse(links_reversed.lias.begin(), links_reversed.lias.end());
    std::mt19937 random(11);
    std::shuffle(mats_shuffled.mats.begin(), mats_shuffled.mats.end(), random);
    for (const Model* model :
         std::initializer_list<const Model*>{&shipped, &links_reversed, &mats_shuffled}) {
        Simulation sim(compile(*model));
        sim.enable_accounting(true);
        const CompiledLevel& lv = sim.model().levels[0];
        ASSERT_GT(lv.grounds.size(), 200u) << "the string's air is a ground on every mass";
        const std::vector<double> expected = chain_and_ground_losses_by_hand(sim, 4800);
        const std::size_t lias = sim.model().source.lias.size();
        int booked = 0;
        for (int j = 1; j < lv.size; ++j)
            if (lv.chain_element[j] >= 0) {
                const int e = lv.chain_element[j];
                EXPECT_EQ(sim.dissipated_by_element()[e], expected[e]) << "link " << e;
                booked += expected[e] > 0;
            }
        for (const CompiledGround& g : lv.grounds) {
            const std::size_t e = lias + g.element;
            EXPECT_EQ(sim.dissipated_by_element()[e], expected[e]) << "ground " << g.element;
            booked += expected[e] > 0;
        }
        EXPECT_GT(booked, 400) << "the bowed string moves, and its dampers take something";
        if (model == &shipped) {
            EXPECT_EQ(lv.chain_element_runs.size(), 1u) << "a string built in order is one run";
            EXPECT_EQ(lv.ground_runs.size(), 1u);
        }
        if (model == &links_reversed) {
            EXPECT_GT(lv.chain_element_runs.size(), 200u);
        }
        if (model == &mats_shuffled) {
            EXPECT_GT(lv.ground_runs.size(), 100u);
        }
    }
}

// With the violin body at the bridge (its modes' oscillators, the bridge a modal point linked
// to the string's end, itself a modal point in the modal structure), the books still balance.
Model string_with_body(Structure structure, int haptic_divider) {
    BowedStringOptions options;
    options.pitch = 220, options.structure = structure, options.haptic_divider = haptic_divider;
    options.body = "violin";
    return build_bowed_string(options);
}

class EnergyWithBody : public ::testing::TestWithParam<Structure> {};

TEST_P(EnergyWithBody, BooksBalanceStepByStep) {
    Simulation sim(compile(string_with_body(GetParam(), 1)));
    const Books books = step_by_step_books(sim, 48000);
    ASSERT_GT(books.scale, 0);
    EXPECT_LT(books.worst, 1e-9 * books.scale);
    // The body's dampers take their share: its modes move.
    const auto& mats = sim.model().source.mats;
    const std::size_t lias = sim.model().source.lias.size();
    double body_loss = 0;
    for (std::size_t m = 0; m < mats.size(); ++m)
        if (mats[m].id.rfind("body", 0) == 0) body_loss += sim.dissipated_by_element()[lias + m];
    EXPECT_GT(body_loss, 0);
}

TEST_P(EnergyWithBody, MultiRateBowingNeverAddsEnergyOverAnyHapticPeriod) {
    Simulation sim(compile(string_with_body(GetParam(), 16)));
    const Books books = haptic_period_books(sim, 16, 3 * 48000 / 16);
    ASSERT_GT(books.scale, 0);
    EXPECT_LE(books.worst, 1e-12 * books.scale);
}

INSTANTIATE_TEST_SUITE_P(Structures, EnergyWithBody,
                         ::testing::Values(Structure::Chain, Structure::Modal));

}  // namespace
}  // namespace archet
