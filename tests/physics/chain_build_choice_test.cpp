// fastest_chain_build() times the builds of the bowed chain's loop on a simulation, then puts its
// state back, and the engine, `render`, `play` and the LV2 plugin then run that build. Which build
// wins is the machine's to say (no test here asserts a speed); what holds everywhere: it picks a
// build this CPU runs, leaves the simulation it measured as it was, picks the widest where there is
// no bowed chain to time, and whichever build run() takes, the sound is the same bytes.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "archet/builders/bowed_chain.hpp"
#include "archet/files/model_file.hpp"
#include "archet/physics/chain_build_choice.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/renderer.hpp"
#include "archet/physics/simulation.hpp"
#include "run_as_step.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

using test::same_bytes;
using test::state_of;
using test::wandering_bow;

std::vector<double> sound_of(Simulation& sim, std::size_t ticks) {
    std::vector<double> sound(ticks);
    EXPECT_EQ(sim.run(sound), ticks);
    return sound;
}

TEST(ChainBuildChoice, LeavesTheSimulationItTimesAsItWas) {
    const Model model = load_model_file(test::resource("models/bowed-string-220-paper.json"));
    const Gesture bow = wandering_bow(5, 0.5);
    Simulation timed(compile(model)), twin(compile(model));
    timed.set_gesture_track(&bow), twin.set_gesture_track(&bow);
    sound_of(timed, 4800), sound_of(twin, 4800);  // the bow has landed

    const ChainBuild chosen = fastest_chain_build(timed);
    EXPECT_TRUE(chain_build_runs_here(chosen)) << chain_build_name(chosen);
    EXPECT_EQ(timed.tick(), twin.tick());
    EXPECT_TRUE(same_bytes(state_of(timed), state_of(twin))) << "its state is untouched";
    EXPECT_EQ(timed.chain_build(), chosen_chain_build()) << "and its build is the caller's to set";
    const std::vector<double> played = sound_of(timed, 2400);
    EXPECT_TRUE(same_bytes(played, sound_of(twin, 2400)));
}

TEST(ChainBuildChoice, EveryBuildRunGivesTheSameBytes) {
    const Model model = load_model_file(test::resource("models/bowed-string-110.json"));
    const Gesture bow = wandering_bow(9, 0.4);
    std::vector<double> widest;
    for (ChainBuild build : {ChainBuild::Avx512, ChainBuild::Avx2, ChainBuild::Plain}) {
        if (!chain_build_runs_here(build)) continue;
        Simulation sim(compile(model));
        sim.set_gesture_track(&bow);
        sim.set_chain_build(build);
        EXPECT_EQ(sim.chain_build(), build);
        const std::vector<double> sound = sound_of(sim, 19200);
        if (widest.empty())
            widest = sound;
        else
            EXPECT_TRUE(same_bytes(sound, widest)) << chain_build_name(build);
    }
    EXPECT_FALSE(widest.empty());
}

TEST(ChainBuildChoice, WithoutABowedChainToTimeItIsTheWidest) {
    Simulation accounted(compile(load_model_file(test::resource("models/bowed-string-220.json"))));
    accounted.enable_accounting(true);  // energy accounts take the general step
    ASSERT_NE(accounted.bowed_chain_misfit(), "");
    EXPECT_EQ(fastest_chain_build(accounted), chosen_chain_build());
}

// A trial that blows up leaves NaN past the storage, in lanes the chain loop's last round writes:
// the state put back after it (load_state()) zeroes them, and plays as its twin's.
TEST(ChainBuildChoice, AStatePutBackForgetsWhatABlownUpRunLeft) {
    const Model model = build_bowed_chain(37);  // its last round runs past the storage
    const Gesture bow = wandering_bow(7, 0.5);
    Simulation blown(compile(model)), twin(compile(model));
    blown.set_gesture_track(&bow), twin.set_gesture_track(&bow);
    sound_of(blown, 4800);
    std::vector<double> state(blown.state_size());
    blown.save_state(state.data());
    CompiledLevel& audio = blown.model().levels[0];
    audio.x()[audio.size - audio.fixed_after] = std::nan("");  // the chain loop's last MAT
    std::vector<double> sound(4800);
    ASSERT_LT(blown.run(sound), sound.size()) << "it blew up";
    blown.load_state(state.data());
    twin.load_state(state.data());
    const std::vector<double> played = sound_of(blown, 2400);
    EXPECT_TRUE(same_bytes(played, sound_of(twin, 2400)));
}

// A render of a second or more runs in the build it finds: the bytes of step().
TEST(ChainBuildChoice, ARenderInTheBuildItFoundGivesTheStepsBytes) {
    const Model model = build_bowed_chain(300);
    const Gesture bow = wandering_bow(3, 1.2);
    Simulation rendered(compile(model)), stepped(compile(model));
    rendered.set_gesture_track(&bow), stepped.set_gesture_track(&bow);
    std::vector<double> sound;
    RenderOptions options;
    options.frames = 48000;
    render(rendered, options,
           [&](const RenderBlock& b) { sound.insert(sound.end(), b.audio, b.audio + b.frames); });
    EXPECT_TRUE(chain_build_runs_here(rendered.chain_build()));
    std::vector<double> expected;
    for (int i = 0; i < 48000; ++i) {
        stepped.step();
        expected.push_back(stepped.output());
    }
    EXPECT_TRUE(same_bytes(sound, expected)) << chain_build_name(rendered.chain_build());
}

}  // namespace
}  // namespace archet
