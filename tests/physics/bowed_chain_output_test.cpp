// The bowed chain's loop takes the sound of a run of velocity outputs (a body's modes, as the
// shipped strings radiate) a vector of divisions at a time: it must still give output()'s
// bytes, in every build, for every length of run, and leave other outputs to output().

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "archet/builders/bowed_string.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/velocity_run.hpp"
#include "run_as_step.hpp"

namespace archet {
namespace {

using test::wandering_bow;

Model shipped_string() {
    BowedStringOptions o;
    o.pitch = 220, o.masses = 60;
    return build_bowed_string(o);
}

// The string's masses s<first> … s<first + count − 1> as its outputs, each its velocity with a
// gain of its own (distinct gains and speeds, so that adding them in another order would show).
Model sounding_masses(int first, int count) {
    Model m = shipped_string();
    m.outputs.clear();
    for (int k = 0; k < count; ++k)
        m.outputs.push_back(
            {"s" + std::to_string(first + k), Output::Signal::Velocity, 0.5 + 0.37 * k});
    return m;
}

// How many outputs the loop divides a vector at a time (0: output() sounds the model).
int velocity_run_length(const Model& model) {
    return find_velocity_run(compile(model)).count;
}

void expect_in_every_build(const Model& model, int ticks) {
    test::expect_run_as_step_in_every_build(model, wandering_bow(11, 0.5), {500, 1, 33}, ticks);
}

TEST(BowedChainOutput, ARunOfVelocitiesSoundsAsOutputDoesInEveryBuild) {
    const Model shipped = shipped_string();
    ASSERT_EQ(shipped.outputs.size(), 6u);
    ASSERT_EQ(velocity_run_length(shipped), 6) << "the body's modes: the shape this is about";
    expect_in_every_build(shipped, 12000);
    // From one output to as many as the loop takes (8), some leaving a vector part full on
    // each build.
    for (int count = 1; count <= kMostVelocityOutputs; ++count) {
        SCOPED_TRACE(std::to_string(count) + " outputs");
        const Model m = sounding_masses(10, count);
        ASSERT_EQ(velocity_run_length(m), count);
        expect_in_every_build(m, 3000);
    }
    // A run that ends at the level's last MAT: its vectors read into the storage's read-ahead.
    Model last = shipped_string();
    const CompiledModel compiled = compile(last);
    const CompiledLevel& audio = compiled.levels[0];
    last.outputs.clear();
    for (int s = audio.size - 2; s <= audio.size; ++s)
        last.outputs.push_back(
            {last.mats[audio.element_of[s]].id, Output::Signal::Velocity, 1.0 + 0.1 * s});
    ASSERT_EQ(velocity_run_length(last), 3);
    expect_in_every_build(last, 3000);
}

TEST(BowedChainOutput, OtherOutputsSoundAsOutputDoes) {
    // Too long a run, a run out of storage order, a gap, and other signals among velocities.
    Model nine = sounding_masses(10, 9);
    Model reversed = sounding_masses(10, 4);
    std::swap(reversed.outputs[0], reversed.outputs[3]);
    Model gap = sounding_masses(10, 4);
    gap.outputs[2].element = "s20";
    Model mixed = shipped_string();
    mixed.outputs[1].signal = Output::Signal::Position;
    mixed.outputs.push_back({"bridge", Output::Signal::Force, 0.01});
    for (const Model* m : {&nine, &reversed, &gap, &mixed}) {
        ASSERT_EQ(velocity_run_length(*m), 0);
        expect_in_every_build(*m, 6000);
    }
}

}  // namespace
}  // namespace archet
