// Simulation::run() steps a bowed chain with a loop written for that shape: it must give the
// bytes of step() then output() at every tick, and leave the same state, whatever the block
// size, the scheme revision, the hand's orientation or what the player changes between blocks.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "archet/builders/bowed_chain.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/simulation.hpp"

namespace archet {
namespace {

// A wandering hand on both axes (the bow lands, sticks, slips, stops and turns back).
Gesture wandering_bow(unsigned seed, double seconds) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> step(-0.03, 0.05), press(0.0005, 0.004);
    std::vector<GestureKeyframe> frames{{0.0, 0.0, 0.0}};
    double x = 0;
    for (double t = 0.03; t <= seconds; t += 0.05)
        frames.push_back({t, x += step(random), press(random)});
    return Gesture("wandering", frames);
}

Model paper_string(double pitch, int masses, double bow_position) {
    BowedStringOptions o;
    o.pitch = pitch;
    o.masses = masses;
    o.paper = true;
    o.bow_position = bow_position;
    o.bow_position_fixed = true;
    return build_bowed_string(o);
}

// With the total force on the bow's two masses kept too (Force probes), which the friction's
// force on them enters.
Model bow_forces_watched(Model m) {
    const Lia* friction = m.find_lia("friction");
    m.probes.push_back({"bowed_force", ProbeKind::Force, friction->to});
    m.probes.push_back({"bow_force", ProbeKind::Force, friction->from});
    return m;
}

// The hand links turned around: from the bow's masses to the gesture points.
Model hands_turned(Model m) {
    auto is_gesture = [&](const std::string& id) {
        const Mat* mat = m.find_mat(id);
        return mat && mat->kind == MatKind::Gesture;
    };
    for (Lia& l : m.lias)
        if (is_gesture(l.from)) std::swap(l.from, l.to);
    return m;
}

std::vector<double> state_of(const Simulation& sim) {
    std::vector<double> state(sim.state_size());
    sim.save_state(state.data());
    return state;
}

bool same_bytes(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// Plays `model` twice along `gesture`, once tick by tick and once by run() in blocks of the
// given sizes (cycled), and holds each block's sound and the state after it to the other's.
void expect_run_as_step(const Model& model, const Gesture& gesture, std::vector<int> blocks,
                        int ticks, int revision = 0) {
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
        ASSERT_EQ(by_run.run(got), static_cast<std::size_t>(size));
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

TEST(BowedChain, RunGivesStepsBytesOnThePapersStrings) {
    const Gesture bow = wandering_bow(1, 1.0);
    expect_run_as_step(paper_string(220, 60, 0.12), bow, {4096}, 48000);
    expect_run_as_step(paper_string(110, 60, 0.3), bow, {64, 1, 7}, 24000);
    expect_run_as_step(paper_string(440, 25, 0.45), bow, {1000}, 24000);
    expect_run_as_step(bow_forces_watched(paper_string(220, 40, 0.2)), bow, {100}, 24000);
}

TEST(BowedChain, RunGivesStepsBytesOnABenchChain) {
    const Gesture bow = wandering_bow(2, 0.5);
    expect_run_as_step(build_bowed_chain(200), bow, {256}, 24000);
}

TEST(BowedChain, RunGivesStepsBytesWithTheHandLinksTurnedAround) {
    const Model turned = hands_turned(paper_string(220, 60, 0.12));
    const CompiledModel compiled = compile(turned);
    for (int i = 0; i < compiled.hand_links; ++i) ASSERT_FALSE(compiled.cross_links[i].hand_is_a);
    expect_run_as_step(turned, wandering_bow(3, 0.5), {333}, 24000);
}

TEST(BowedChain, RunComputesAsTheRevisionItIsAskedFor) {
    expect_run_as_step(paper_string(220, 60, 0.12), wandering_bow(4, 0.5), {512}, 24000, 3);
}

// Between blocks the player moves the live device and changes parameters; run() and step()
// then go on from the same state.
TEST(BowedChain, RunFollowsTheDeviceAndParametersBetweenBlocks) {
    const Model model = paper_string(220, 60, 0.12);
    Simulation by_step(compile(model)), by_run(compile(model));
    for (Simulation* sim : {&by_step, &by_run}) sim->set_gesture_track(nullptr);
    const ParameterSlot mu_s = by_run.model().resolve_parameter({"friction", "mu_s"});
    const ParameterSlot mass = by_run.model().resolve_parameter({"s10", "mass"});
    std::vector<double> expected(240), got(240);
    for (int block = 0; block < 100; ++block) {
        const GestureSample hand{0.002 * block, 0.0005 + 0.00003 * block};
        for (Simulation* sim : {&by_step, &by_run}) {
            sim->set_device_position(hand);
            if (block == 40) sim->write_slot(mu_s, 0.6);
            if (block == 70) sim->write_slot(mass, 1.2 * sim->read_slot(mass));
        }
        for (double& sample : expected) {
            by_step.step();
            sample = by_step.output();
        }
        ASSERT_EQ(by_run.run(got), got.size());
        ASSERT_EQ(std::memcmp(expected.data(), got.data(), got.size() * sizeof(double)), 0)
            << "block " << block;
        ASSERT_TRUE(same_bytes(state_of(by_step), state_of(by_run))) << "block " << block;
    }
    // Ticks stepped one by one carry on from a block as from any other tick.
    for (int i = 0; i < 100; ++i) {
        by_step.step(), by_run.step();
        ASSERT_EQ(by_step.output(), by_run.output());
    }
}

TEST(BowedChain, AnEmptyBlockChangesNothing) {
    const Model model = paper_string(220, 60, 0.12);
    Simulation untouched(compile(model)), ran(compile(model));
    EXPECT_EQ(ran.run({}), 0u);
    EXPECT_TRUE(same_bytes(state_of(untouched), state_of(ran)));
}

// Whatever run() does not write for its shape, it steps as step() does; and it says why.
TEST(BowedChain, OtherShapesRunTheGeneralStepAndSaySo) {
    BowedStringOptions o;
    o.pitch = 220;
    Simulation body(compile(build_bowed_string(o)));
    EXPECT_NE(body.bowed_chain_misfit(), "");
    o.body = "none";
    Simulation losses(compile(build_bowed_string(o)));
    EXPECT_NE(losses.bowed_chain_misfit(), "");
    const Gesture bow = wandering_bow(5, 0.3);
    for (Simulation* sim : {&body, &losses}) {
        Simulation twin(compile(sim->model().source));
        sim->set_gesture_track(&bow), twin.set_gesture_track(&bow);
        std::vector<double> got(4800);
        ASSERT_EQ(sim->run(got), got.size());
        for (double sample : got) {
            twin.step();
            ASSERT_EQ(twin.output(), sample);
        }
    }
}

// A tick whose sound is not finite ends the block there, as the renderer reports it.
TEST(BowedChain, RunStopsAfterTheFirstTickThatIsNotFinite) {
    Model model = paper_string(220, 60, 0.12);
    Simulation by_step(compile(model)), by_run(compile(model));
    const Gesture bow = wandering_bow(6, 0.2);
    by_step.set_gesture_track(&bow), by_run.set_gesture_track(&bow);
    const ParameterSlot mass = by_run.model().resolve_parameter({"s10", "mass"});
    std::vector<double> warm(2000);
    by_run.run(warm);
    for (std::size_t i = 0; i < warm.size(); ++i) by_step.step();
    // Far past the scheme's bound: a mass a million times lighter blows the chain up.
    by_step.write_slot(mass, 1e-6 * by_step.read_slot(mass));
    by_run.write_slot(mass, 1e-6 * by_run.read_slot(mass));
    int first_not_finite = 0;
    while (std::isfinite((by_step.step(), by_step.output()))) ++first_not_finite;
    std::vector<double> got(100000);
    const std::size_t ran = by_run.run(got);
    EXPECT_EQ(ran, static_cast<std::size_t>(first_not_finite) + 1);
    EXPECT_FALSE(std::isfinite(got[ran - 1]));
    EXPECT_EQ(by_run.tick(), by_step.tick());
}

}  // namespace
}  // namespace archet
