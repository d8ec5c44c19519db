// Simulation::run() steps a bowed chain with a loop written for that shape: it must give the
// bytes of step() then output() at every tick, and leave the same state, whatever the block
// size, the scheme revision, the hand's orientation or what the player changes between blocks.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "archet/builders/bowed_chain.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/blow_up.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/parameter_smoother.hpp"
#include "archet/physics/renderer.hpp"
#include "archet/physics/simulation.hpp"
#include "run_as_step.hpp"
#include "second_bow.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

using test::expect_run_as_step;
using test::expect_run_as_step_in_every_build;
using test::same_bytes;
using test::state_of;
using test::wandering_bow;

// What `archet new bowed-string` writes: losses to ground along the string, a violin body at
// the bridge through a link, the bow's hair on a modal point over three masses.
Model shipped_string(double pitch, int masses) {
    BowedStringOptions o;
    o.pitch = pitch;
    o.masses = masses;
    return build_bowed_string(o);
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

TEST(BowedChain, RunGivesStepsBytesOnThePapersStrings) {
    const Gesture bow = wandering_bow(1, 1.0);
    expect_run_as_step(paper_string(220, 60, 0.12), bow, {4096}, 48000);
    expect_run_as_step(paper_string(110, 60, 0.3), bow, {64, 1, 7}, 24000);
    expect_run_as_step(paper_string(440, 25, 0.45), bow, {1000}, 24000);
    expect_run_as_step(bow_forces_watched(paper_string(220, 40, 0.2)), bow, {100}, 24000);
}

// The loop is built for each instruction set, as the chain loop is; the general step takes the
// widest, and every build gives its bytes.
TEST(BowedChain, RunGivesStepsBytesInEveryBuildThisCpuRuns) {
    const Gesture bow = wandering_bow(5, 0.5);
    for (ChainBuild build : {ChainBuild::Plain, ChainBuild::Avx2, ChainBuild::Avx512}) {
        if (!chain_build_runs_here(build)) {
            RecordProperty(std::string(chain_build_name(build)) + "_build",
                           "not run: not this CPU's");
            continue;
        }
        SCOPED_TRACE(chain_build_name(build));
        expect_run_as_step(paper_string(220, 60, 0.12), bow, {480}, 24000, 0, build);
        expect_run_as_step(build_bowed_chain(37), bow, {64}, 12000, 0, build);
        expect_run_as_step(shipped_string(220, 60), bow, {480}, 12000, 0, build);
    }
}

TEST(BowedChain, RunGivesStepsBytesOnABenchChain) {
    const Gesture bow = wandering_bow(2, 0.5);
    expect_run_as_step(build_bowed_chain(200), bow, {256}, 24000);
}

TEST(BowedChain, RunGivesStepsBytesWithTheHandLinksTurnedAround) {
    const Model turned = hands_turned(paper_string(220, 60, 0.12));
    const CompiledModel compiled = compile(turned);
    ASSERT_EQ(compiled.hand_links, 2);
    for (int i = 0; i < compiled.hand_links; ++i) ASSERT_FALSE(compiled.cross_links[i].hand_is_a);
    expect_run_as_step(turned, wandering_bow(3, 0.5), {333}, 24000);
}

TEST(BowedChain, RunComputesAsTheRevisionItIsAskedFor) {
    expect_run_as_step(paper_string(220, 60, 0.12), wandering_bow(4, 0.5), {512}, 24000, 3);
}

using Change = std::tuple<std::string, std::string, double>;  // element, parameter, factor

// Plays `model` from the live device, moving it and making the `changes` in turn between
// blocks, and holds run() to step() after each.
void expect_run_follows_changes(const Model& model, const std::vector<Change>& made) {
    Simulation by_step(compile(model)), by_run(compile(model));
    for (Simulation* sim : {&by_step, &by_run}) sim->set_gesture_track(nullptr);
    ASSERT_EQ(by_run.bowed_chain_misfit(), "");
    std::vector<std::pair<ParameterSlot, double>> changes;
    for (const auto& [element, parameter, factor] : made)
        changes.push_back({by_run.model().resolve_parameter({element, parameter}), factor});
    std::vector<double> expected(240), got(240);
    int sounding = 0;
    // From block 30, a change every ten blocks, each one made.
    const int blocks = 40 + 10 * static_cast<int>(changes.size());
    for (int block = 0; block < blocks; ++block) {
        const GestureSample hand{0.002 * block, 0.0005 + 0.00003 * block};
        for (Simulation* sim : {&by_step, &by_run}) {
            sim->set_device_position(hand);
            if (block >= 30 && block % 10 == 0) {
                const auto& [slot, factor] = changes[(block / 10 - 3) % changes.size()];
                sim->write_slot(slot, factor * sim->read_slot(slot));
            }
        }
        for (double& sample : expected) {
            by_step.step();
            sample = by_step.output();
        }
        ASSERT_EQ(by_run.run(got), got.size());
        ASSERT_EQ(std::memcmp(expected.data(), got.data(), got.size() * sizeof(double)), 0)
            << "block " << block;
        ASSERT_TRUE(same_bytes(state_of(by_step), state_of(by_run))) << "block " << block;
        for (double sample : got) sounding += sample != 0.0;
    }
    EXPECT_GT(sounding, 12000) << "the string hardly sounded: the comparison proves little";
    // Ticks stepped one by one carry on from a block as from any other tick.
    for (int i = 0; i < 100; ++i) {
        by_step.step(), by_run.step();
        ASSERT_EQ(by_step.output(), by_run.output());
    }
}

// Between blocks the player moves the live device and changes parameters; run() and step()
// then go on from the same state.
TEST(BowedChain, RunFollowsTheDeviceAndParametersBetweenBlocks) {
    const Model model = paper_string(220, 60, 0.12);
    const CompiledModel compiled = compile(model);
    const std::string bowed = model.mats[compiled.bows[0].string - 1].id;
    // What the loop reads once per block: the friction, the masses of the bowed pair, a hand
    // link, the bow's pressure buffer; and a mass of the chain.
    expect_run_follows_changes(model, {{"friction", "mu_s", 0.75},
                                       {"s10", "mass", 1.2},
                                       {bowed, "mass", 0.9},
                                       {"bow", "mass", 1.5},
                                       {"bow_hold", "stiffness", 0.8},
                                       {"press_hold", "damping", 1.3},
                                       {"friction", "buffer_stiffness", 1.4}});
}

// The same on the shipped string: also a mass under the bow's hair (which moves the response of
// its contact point), a string mass's ground and a body mode.
TEST(BowedChain, RunFollowsTheDeviceAndParametersBetweenBlocksOnTheShippedString) {
    expect_run_follows_changes(shipped_string(220, 60), {{"friction", "mu_s", 0.75},
                                                         {"s7", "mass", 1.2},
                                                         {"s30", "damping", 3.0},
                                                         {"body1", "mass", 0.8},
                                                         {"body2", "stiffness", 1.3},
                                                         {"bow", "mass", 1.5},
                                                         {"press_hold", "damping", 1.3},
                                                         {"friction", "buffer_stiffness", 1.4}});
}

// A rest length given to a chain link takes the general step; glided back to 0 as the studio
// glides a knob (the glide's end refreshes the chain loop's runs), the loop again, on the same
// bytes.
TEST(BowedChain, AChainLinksRestLengthSetBackToZeroReturnsToTheLoop) {
    // The link turned around (from s21 to s20): its length is stored negated, and a zero one
    // must be +0, the bits of no length.
    Model model = paper_string(220, 60, 0.12);
    Lia* turned = model.find_lia("k20");
    std::swap(turned->from, turned->to);
    const Gesture bow = wandering_bow(6, 0.5);
    Simulation by_step(compile(model)), by_run(compile(model));
    const ParameterSlot length = by_run.model().resolve_parameter({"k20", "length"});
    std::vector<double> expected(4800), got(4800);
    auto expect_same_block = [&](const char* when) {
        for (double& sample : expected) {
            by_step.step();
            sample = by_step.output();
        }
        ASSERT_EQ(by_run.run(got), got.size());
        ASSERT_EQ(std::memcmp(expected.data(), got.data(), got.size() * sizeof(double)), 0) << when;
        ASSERT_TRUE(same_bytes(state_of(by_step), state_of(by_run))) << when;
        EXPECT_GT(std::count_if(got.begin(), got.end(), [](double y) { return y != 0.0; }), 2400)
            << when << ": the string hardly sounded, the comparison proves little";
    };
    for (Simulation* sim : {&by_step, &by_run}) sim->set_gesture_track(&bow);
    expect_same_block("before the length");
    for (Simulation* sim : {&by_step, &by_run}) sim->write_slot(length, 0.0001);
    EXPECT_EQ(by_run.bowed_chain_misfit(), "its chain links have been given rest lengths");
    expect_same_block("with the length");
    ParameterSmoother step_knob, run_knob;
    step_knob.glide(by_step, length, 0.0, 480);
    run_knob.glide(by_run, length, 0.0, 480);
    while (run_knob.active() > 0) {  // a glide moves its slot at every tick
        step_knob.advance(by_step), run_knob.advance(by_run);
        by_step.step(), by_run.step();
        ASSERT_EQ(by_step.output(), by_run.output());
    }
    EXPECT_EQ(by_run.bowed_chain_misfit(), "");
    EXPECT_FALSE(std::signbit(by_run.model().levels[0].chain_length[length.index]));
    expect_same_block("with the length back to 0");
}

// The shipped strings, as built and as shipped, and without their body or with a point bow:
// the loop takes their grounds in the chain's rounds and their body and bow's modal points
// as integrate() does.
TEST(BowedChain, RunGivesStepsBytesOnTheShippedStrings) {
    const Gesture bow = wandering_bow(7, 0.5);
    const Model violin = shipped_string(220, 60);
    const CompiledModel compiled = compile(violin);
    const CompiledLevel& audio = compiled.levels[0];
    ASSERT_TRUE(grounds_in_chain_loop(audio));
    ASSERT_FALSE(audio.links.empty());
    ASSERT_GE(audio.modal_point_of[compiled.bows[0].string], 0) << "the hair's contact point";
    expect_run_as_step(violin, bow, {4096}, 24000);
    BowedStringOptions o;
    o.pitch = 330, o.body = "none";
    expect_run_as_step(build_bowed_string(o), bow, {64, 1, 7}, 24000);
    o.body = "violin", o.point_bow = true;
    expect_run_as_step(build_bowed_string(o), bow, {1000}, 24000);
    // A bow on the hair's middle mass, which the hair's point reads and follows.
    Model on_a_mode = shipped_string(220, 60);
    Lia* friction = on_a_mode.find_lia("friction");
    friction->to = on_a_mode.find_mat(friction->bowed_string())->modes[1];
    expect_run_as_step(on_a_mode, bow, {333}, 12000);
    // Each of the loop's four builds by grounds and body (the paper's string, above, has
    // neither), and the string in modal form, every point on every mode.
    o = {};
    o.pitch = 220, o.with_gesture = false;
    auto expect_shape = [&](bool grounds, bool body, const char* what) {
        SCOPED_TRACE(what);
        const Model model = build_bowed_string(o);
        const CompiledLevel audio = compile(model).levels[0];
        ASSERT_EQ(grounds_in_chain_loop(audio), grounds);
        ASSERT_EQ(!audio.links.empty() || !audio.modal_points.empty(), body);
        expect_run_as_step(model, bow, {777}, 12000);
    };
    o.body = "none", o.point_bow = true;
    expect_shape(true, false, "grounds without a body");
    o.body = "violin", o.point_bow = false, o.string_damping = 0.001;
    expect_shape(false, true, "a body without grounds (the string's losses in its links)");
    o.string_damping = -1.0, o.structure = Structure::Modal, o.paper = true, o.masses = 60;
    expect_shape(true, true, "a modal string");
    for (const char* file :
         {"models/bowed-string-110.json", "models/bowed-string-440-harmonic.json",
          "models/bowed-string-880.json"}) {
        SCOPED_TRACE(file);
        expect_run_as_step(load_model_file(test::resource(file)), bow, {480}, 12000);
    }
}

TEST(BowedChain, AnEmptyBlockChangesNothing) {
    const Model model = paper_string(220, 60, 0.12);
    Simulation untouched(compile(model)), ran(compile(model));
    EXPECT_EQ(ran.run({}), 0u);
    EXPECT_TRUE(same_bytes(state_of(untouched), state_of(ran)));
}

// run() against step() then output(), sound and state, over a tenth of a second of a bow
// wandering along and into the string.
void expect_run_gives_steps_bytes(Simulation& sim, bool accounting) {
    const Gesture bow = wandering_bow(5, 0.3);
    Simulation twin(compile(sim.model().source));
    twin.enable_accounting(accounting);
    sim.set_gesture_track(&bow), twin.set_gesture_track(&bow);
    std::vector<double> got(4800);
    ASSERT_EQ(sim.run(got), got.size());
    for (double sample : got) {
        twin.step();
        const double expected = twin.output();
        ASSERT_EQ(std::memcmp(&expected, &sample, sizeof sample), 0);
    }
    EXPECT_TRUE(same_bytes(state_of(sim), state_of(twin)));
}

// A finger stopping the string is solved in the loop after the modal points and before the bow,
// as step() solves it, in every build: on the shipped string, between the hair's masses (each of
// the finger and the bow then moves what the other reads), between the bridge's modal point and
// the string with the hair on the string's first masses, on the paper's string (no body), and
// while the player moves and lifts it.
TEST(BowedChain, RunGivesStepsBytesWithAFinger) {
    BowedStringOptions o;
    o.pitch = 220, o.finger = true, o.finger_position = 0.75;
    const Model fingered = build_bowed_string(o);
    ASSERT_EQ(compile(fingered).levels[0].fingers.size(), 1u);
    Model under_the_hair = fingered;
    const std::vector<std::string>& hair = under_the_hair.find_mat("bow_contact")->modes;
    Lia& finger = *under_the_hair.find_lia("finger");
    const auto first = std::find(finger.along.begin(), finger.along.end(), hair[0]);
    ASSERT_LT(first + 1, finger.along.end());
    ASSERT_EQ(first[1], hair[1]);
    finger.finger_position =
        (static_cast<double>(first - finger.along.begin()) + 0.5) / (finger.along.size() - 1.0);
    o.masses = 63, o.finger_position = 1.0 / 128;  // finger_test.cpp's bridge-end finger
    Model at_the_bridge = build_bowed_string(o);
    at_the_bridge.find_mat("bow_contact")->modes = {"s1", "s2", "s3"};
    o.paper = true, o.masses = 60, o.finger_position = 0.75;
    const Model paper = build_bowed_string(o);
    const Gesture bow = wandering_bow(9, 0.5);
    expect_run_as_step_in_every_build(fingered, bow, {480, 1, 7}, 12000);
    expect_run_as_step_in_every_build(under_the_hair, bow, {333}, 12000);
    expect_run_as_step_in_every_build(at_the_bridge, bow, {500}, 12000);
    expect_run_as_step_in_every_build(paper, bow, {777}, 12000);
    expect_run_follows_changes(fingered, {{"finger", "position", 0.8},
                                          {"finger", "pressure", 0.5},
                                          {"finger", "position", 1.2},
                                          {"finger", "pressure", 0.0}});
}

// Whatever run() does not write for its shape, it steps as step() does; and it says why.
TEST(BowedChain, OtherShapesRunTheGeneralStepAndSaySo) {
    Simulation accounted(compile(shipped_string(220, 60)));
    accounted.enable_accounting(true);
    EXPECT_EQ(accounted.bowed_chain_misfit(), "it keeps energy accounts");
    Model controlled = shipped_string(220, 60);  // the bow's friction on an envelope
    Control envelope;
    envelope.id = "mu", envelope.target = {"friction", "mu_s"};
    envelope.envelope = {{0.0, 0.3}, {0.3, 0.5}};
    envelope.minimum = 0.1, envelope.maximum = 1.0;
    controlled.controls.push_back(envelope);
    validate_model(controlled);
    Simulation with_control(compile(controlled));
    EXPECT_EQ(with_control.bowed_chain_misfit(), "it has controls");
    for (Simulation* sim : {&accounted, &with_control})
        expect_run_gives_steps_bytes(*sim, sim == &accounted);
}

// The shapes the loop's frame has no place for: the hand at audio rate, a second bow, more than
// four hand links, a link across the rates that is not the hand's, and a hand link holding a
// mass at a rate between the audio's and the hand's.
TEST(BowedChain, ShapesWithoutAPlaceInTheLoopRunTheGeneralStepAndSaySo) {
    const auto misfit_of = [](const Model& model) {
        validate_model(model);
        Simulation sim(compile(model));
        expect_run_gives_steps_bytes(sim, false);
        return sim.bowed_chain_misfit();
    };
    Model hand_at_audio_rate = shipped_string(220, 60);
    for (const char* hand : {"hand_slide", "hand_press"})
        hand_at_audio_rate.find_mat(hand)->rate = "audio";
    EXPECT_EQ(misfit_of(hand_at_audio_rate), "gesture points run at audio rate");

    Model two_bows = shipped_string(220, 60);  // a second bow, resting on s40
    test::add_second_bow(two_bows, "s40");
    EXPECT_EQ(misfit_of(two_bows), "it has no bow, or more than one");

    Model five_hand_links = shipped_string(220, 60);
    for (const char* mass : {"s20", "s30", "s40"}) {
        Lia hold = *five_hand_links.find_lia("bow_hold");
        hold.id = std::string("hold_") + mass, hold.to = mass, hold.stiffness = 1.0;
        hold.damping = 0.01;
        five_hand_links.lias.push_back(hold);
    }
    EXPECT_EQ(misfit_of(five_hand_links), "more than 4 hand links hold it");

    Model across_the_rates = shipped_string(220, 60);  // a mass at the hand's rate, on the bow
    Mat arm;
    arm.id = "arm", arm.kind = MatKind::Mass, arm.rate = "haptic", arm.mass = 1.0;
    across_the_rates.mats.push_back(arm);
    Lia arm_link = *across_the_rates.find_lia("bow_hold");
    arm_link.id = "arm_link", arm_link.from = "arm", arm_link.stiffness = 1.0;
    arm_link.damping = 0.01;
    across_the_rates.lias.push_back(arm_link);
    EXPECT_EQ(misfit_of(across_the_rates), "links join its rate levels besides the hand's");

    Model held_between_the_rates = shipped_string(220, 60);  // a wrist at 12 kHz, held by hand
    held_between_the_rates.rates.push_back({"wrist", 4});
    Mat wrist;
    wrist.id = "wrist", wrist.kind = MatKind::Mass, wrist.rate = "wrist", wrist.mass = 1.0;
    held_between_the_rates.mats.push_back(wrist);
    Lia wrist_hold = *held_between_the_rates.find_lia("bow_hold");
    wrist_hold.id = "wrist_hold", wrist_hold.rate = "wrist", wrist_hold.to = "wrist";
    held_between_the_rates.lias.push_back(wrist_hold);
    EXPECT_EQ(misfit_of(held_between_the_rates), "a hand link does not hold a mass at audio rate");
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
    std::vector<double> expected;
    while (expected.size() < 100000 && (expected.empty() || std::isfinite(expected.back()))) {
        by_step.step();
        expected.push_back(by_step.output());
    }
    ASSERT_FALSE(std::isfinite(expected.back())) << "the string did not blow up";
    std::vector<double> got(100000);
    const std::size_t ran = by_run.run(got);
    ASSERT_EQ(ran, expected.size());
    EXPECT_EQ(std::memcmp(expected.data(), got.data(), ran * sizeof(double)), 0);
    EXPECT_EQ(by_run.tick(), by_step.tick());
}

// The renderer without probes runs blocks: a blow-up is reported as stepping tick by tick
// reports it, at the same tick, naming the same element, with nothing of its block handed on.
TEST(BowedChain, TheRendererReportsABlowUpAsTickByTick) {
    const Model model = paper_string(220, 60, 0.12);
    const Gesture bow = wandering_bow(7, 0.5);
    auto blown = [&](Simulation& sim) {
        sim.set_gesture_track(&bow);
        const ParameterSlot mass = sim.model().resolve_parameter({"s10", "mass"});
        for (int i = 0; i < 2000; ++i) sim.step();
        sim.write_slot(mass, 1e-6 * sim.read_slot(mass));
    };
    Simulation by_step(compile(model)), by_render(compile(model));
    blown(by_step), blown(by_render);
    std::string expected;
    try {
        for (int i = 0; i < 100000; ++i) {
            by_step.step();
            if (!std::isfinite(by_step.output())) throw_blow_up(by_step);
        }
    } catch (const InputError& e) {
        expected = e.what();
    }
    ASSERT_NE(expected, "") << "the string did not blow up";
    RenderOptions options;
    options.frames = 100000;
    options.block_frames = 4096;
    std::uint64_t handed = 0;
    try {
        render(by_render, options, [&](const RenderBlock& b) { handed += b.frames; });
        FAIL() << "the render did not report the blow-up";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), expected);
    }
    EXPECT_EQ(by_render.tick(), by_step.tick());
    EXPECT_LT(handed, by_render.tick() - 2000);
    EXPECT_EQ(handed % options.block_frames, 0u);
}

}  // namespace
}  // namespace archet
