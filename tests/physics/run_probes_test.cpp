// Simulation::run() with probe rows: the engine and the renderer read the probes after every
// tick through it, so it must give, row by row, the bytes of step(), output() and probe(), on a
// bowed chain (its own loop) and on the general step alike, and leave the energy's columns to
// the caller when asked.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "archet/analysis/bow_probes.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/run_ticks.hpp"
#include "archet/physics/simulation.hpp"
#include "run_as_step.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

using test::same_bytes;
using test::state_of;
using test::wandering_bow;

bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

bool is_energy(const Simulation& sim, std::size_t probe) {
    return sim.model().probes[probe].kind == ProbeKind::Energy;
}

// Plays `model` tick by tick and by run() with probe rows in blocks of the given sizes
// (cycled), and holds every sample and every probe of every row to the other's. Without
// `energy`, the energy's columns must keep what they held. Returns how many probe values
// differed from zero, so that a caller can tell the probes moved.
int expect_rows_as_step(const Model& model, std::vector<int> blocks, int ticks, bool energy,
                        bool accounting = false) {
    validate_model(model);
    const Gesture bow = wandering_bow(11, 0.5);
    Simulation by_step(compile(model)), by_run(compile(model));
    by_step.enable_accounting(accounting), by_run.enable_accounting(accounting);
    by_step.set_gesture_track(&bow), by_run.set_gesture_track(&bow);
    const std::size_t count = by_run.probe_count();
    constexpr double kUntouched = -1234.5;
    int moving = 0, done = 0, block = 0;
    while (done < ticks) {
        const int size = std::min(blocks[block++ % blocks.size()], ticks - done);
        std::vector<double> sound(size), rows(size * count, kUntouched);
        const std::size_t ran = by_run.run(sound, {.values = rows.data(), .energy = energy});
        EXPECT_EQ(ran, static_cast<std::size_t>(size)) << model.name;
        for (int i = 0; i < size; ++i) {
            by_step.step();
            EXPECT_TRUE(same_bits(by_step.output(), sound[i]))
                << model.name << ": tick " << done + i << ": the sound";
            for (std::size_t p = 0; p < count; ++p) {
                const double got = rows[i * count + p];
                const bool left = !energy && is_energy(by_run, p);
                const double expected = left ? kUntouched : by_step.probe(p);
                if (!same_bits(expected, got)) {
                    ADD_FAILURE() << model.name << ": tick " << done + i << ": probe "
                                  << by_run.model().probes[p].id << " read " << got
                                  << " where step() then probe() read " << expected;
                    return moving;
                }
                moving += !left && got != 0.0;
            }
        }
        EXPECT_TRUE(same_bytes(state_of(by_step), state_of(by_run)))
            << model.name << ": the states differ after tick " << done + size;
        done += size;
    }
    return moving;
}

const char* const kShipped[] = {"models/bowed-string-220-paper.json",
                                "models/bowed-string-110.json",
                                "models/bowed-string-440-harmonic.json"};

TEST(RunProbes, EveryProbeOfTheShippedStringsReadsAsAfterStep) {
    for (const char* file : kShipped) {
        SCOPED_TRACE(file);
        const Model model = load_model_file(test::resource(file));
        ASSERT_EQ(Simulation(compile(model)).bowed_chain_misfit(), "") << "the loop's own shape";
        std::vector<ProbeKind> kinds;
        for (const Probe& p : model.probes) kinds.push_back(p.kind);
        for (ProbeKind kind : {ProbeKind::Position, ProbeKind::Velocity, ProbeKind::Force,
                               ProbeKind::NormalForce, ProbeKind::FrictionForce,
                               ProbeKind::SlipVelocity, ProbeKind::Energy, ProbeKind::PowerIn})
            ASSERT_NE(std::find(kinds.begin(), kinds.end(), kind), kinds.end())
                << "the model has a probe of every kind";
        const int moving = expect_rows_as_step(model, {16, 1, 37, 480}, 12000, true);
        EXPECT_GT(moving, 12000 * static_cast<int>(model.probes.size()) / 2)
            << "most probes read something other than zero";
    }
}

TEST(RunProbes, TheGeneralStepReadsItsProbesTheSameWay) {
    // Energy accounts take a model off the bowed chain's loop.
    const Model model = load_model_file(test::resource(kShipped[0]));
    Simulation accounted(compile(model));
    accounted.enable_accounting(true);
    ASSERT_NE(accounted.bowed_chain_misfit(), "");
    EXPECT_GT(expect_rows_as_step(model, {16, 5}, 4800, true, true), 0);
}

TEST(RunProbes, WithoutEnergyItsColumnsKeepWhatTheyHeld) {
    for (const char* file : kShipped) {
        SCOPED_TRACE(file);
        expect_rows_as_step(load_model_file(test::resource(file)), {16, 3}, 4800, false);
    }
    const Model model = load_model_file(test::resource(kShipped[1]));
    expect_rows_as_step(model, {16}, 2400, false, true);
}

// run_ticks(), as the analyses read a stroke (the map, the stroke search, attacks, bowing
// reports): each tick's sample and its row of the bow's probes, as step() then output() and
// probe() give them, across its blocks, and it stops where it is told.
TEST(RunProbes, RunTicksHandsEveryTickAsStepWould) {
    Model model = load_model_file(test::resource(kShipped[1]));
    ASSERT_TRUE(read_bow_only(model, {ProbeKind::SlipVelocity, ProbeKind::NormalForce}));
    ASSERT_EQ(model.probes.size(), 2u);
    EXPECT_EQ(model.probes[0].id, "slip_velocity");
    EXPECT_EQ(model.probes[1].kind, ProbeKind::NormalForce);
    const Gesture bow = wandering_bow(11, 0.5);
    Simulation by_step(compile(model)), by_ticks(compile(model));
    by_step.set_gesture_track(&bow), by_ticks.set_gesture_track(&bow);
    constexpr std::size_t kTicks = 10000;  // across many of its blocks
    std::size_t next = 0;
    int slipping = 0;
    const std::size_t handed =
        run_ticks(by_ticks, kTicks, [&](std::size_t tick, double sample, const double* row) {
            EXPECT_EQ(tick, next++);
            by_step.step();
            EXPECT_TRUE(same_bits(sample, by_step.output())) << "tick " << tick;
            EXPECT_TRUE(same_bits(row[0], by_step.probe(0))) << "tick " << tick;
            EXPECT_TRUE(same_bits(row[1], by_step.probe(1))) << "tick " << tick;
            slipping += row[0] != 0.0;
            return true;
        });
    EXPECT_EQ(handed, kTicks);
    EXPECT_GT(slipping, 100) << "the bow slips now and then";
    // Told to stop at a tick, it hands no later one.
    Simulation stopped(compile(model));
    stopped.set_gesture_track(&bow);
    std::size_t last = 0;
    EXPECT_EQ(run_ticks(stopped, kTicks,
                        [&](std::size_t tick, double, const double*) {
                            last = tick;
                            return tick < 5000;
                        }),
              5001u);
    EXPECT_EQ(last, 5000u);
}

TEST(RunProbes, RunTicksGoesOnPastATickThatIsNotFinite) {
    // run() ends its block after such a tick; the steps go on, and so does run_ticks().
    Model model = load_model_file(test::resource(kShipped[0]));
    model.find_mat("s12")->position = std::numeric_limits<double>::quiet_NaN();
    ASSERT_TRUE(read_bow_only(model, {ProbeKind::SlipVelocity}));
    Simulation by_step(compile(model)), by_ticks(compile(model));
    int not_finite = 0;
    EXPECT_EQ(run_ticks(by_ticks, 300,
                        [&](std::size_t tick, double sample, const double*) {
                            by_step.step();
                            const double expected = by_step.output();
                            EXPECT_EQ(std::isfinite(sample), std::isfinite(expected)) << tick;
                            if (std::isfinite(expected)) {
                                EXPECT_TRUE(same_bits(sample, expected)) << tick;
                            }
                            not_finite += !std::isfinite(sample);
                            return true;
                        }),
              300u);
    EXPECT_GT(not_finite, 200) << "the sound is NaN once the NaN has reached the bridge";
    Model bowless = model;
    std::erase_if(bowless.lias, [](const Lia& l) { return l.kind == LiaKind::BowFriction; });
    EXPECT_FALSE(read_bow_only(bowless, {ProbeKind::SlipVelocity}));
    EXPECT_EQ(bowless.probes.size(), model.probes.size()) << "left as it was";
}

}  // namespace
}  // namespace archet
