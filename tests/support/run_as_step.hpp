#pragma once
// Holding Simulation::run() to step() then output(): the bowed chain's loop must give their
// bytes at every tick and leave the same state. Shared by the tests of the loop's shapes.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include "archet/model/gesture.hpp"
#include "archet/model/model.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/simulation.hpp"

namespace archet::test {

/// A wandering hand on both axes (the bow lands, sticks, slips, stops and turns back).
inline Gesture wandering_bow(unsigned seed, double seconds) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> step(-0.03, 0.05), press(0.0005, 0.004);
    std::vector<GestureKeyframe> frames{{0.0, 0.0, 0.0}};
    double x = 0;
    for (double t = 0.03; t <= seconds; t += 0.05)
        frames.push_back({t, x += step(random), press(random)});
    return Gesture("wandering", frames);
}

inline std::vector<double> state_of(const Simulation& sim) {
    std::vector<double> state(sim.state_size());
    sim.save_state(state.data());
    return state;
}

inline bool same_bytes(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

/// Plays `model` twice along `gesture`, once tick by tick and once by run() in blocks of the
/// given sizes (cycled), and holds each block's sound and the state after it to the other's.
inline void expect_run_as_step(const Model& model, const Gesture& gesture, std::vector<int> blocks,
                               int ticks, int revision = 0,
                               ChainBuild build = chosen_chain_build()) {
    validate_model(model);
    Simulation by_step(compile(model)), by_run(compile(model));
    if (revision) by_step.compute_as_of(revision), by_run.compute_as_of(revision);
    by_step.set_gesture_track(&gesture);
    by_run.set_gesture_track(&gesture);
    ASSERT_EQ(by_run.bowed_chain_misfit(), "") << model.name;
    int done = 0, block = 0, sounding = 0;
    while (done < ticks) {
        const int size = std::min(blocks[block++ % blocks.size()], ticks - done);
        std::vector<double> expected(size), got(size);
        for (double& sample : expected) {
            by_step.step();
            sample = by_step.output();
        }
        ASSERT_EQ(by_run.run(got, build), static_cast<std::size_t>(size));
        for (int i = 0; i < size; ++i) {
            ASSERT_EQ(std::memcmp(&expected[i], &got[i], sizeof(double)), 0)
                << model.name << ": tick " << done + i << ": " << expected[i] << " by step(), "
                << got[i] << " by run()";
            sounding += expected[i] != 0.0;
        }
        ASSERT_TRUE(same_bytes(state_of(by_step), state_of(by_run)))
            << model.name << ": the states differ after tick " << done + size;
        ASSERT_EQ(by_step.hand_work(), by_run.hand_work());
        ASSERT_EQ(by_step.device_force().slide, by_run.device_force().slide);
        done += size;
    }
    EXPECT_GT(sounding, ticks / 2) << model.name << " was silent: the comparison proves little";
}

/// expect_run_as_step() in each build of the loop this CPU runs (plain, AVX2, AVX-512).
inline void expect_run_as_step_in_every_build(const Model& model, const Gesture& gesture,
                                              const std::vector<int>& blocks, int ticks) {
    for (ChainBuild build : {ChainBuild::Plain, ChainBuild::Avx2, ChainBuild::Avx512}) {
        if (!chain_build_runs_here(build)) continue;
        SCOPED_TRACE(chain_build_name(build));
        expect_run_as_step(model, gesture, blocks, ticks, 0, build);
    }
}

}  // namespace archet::test
