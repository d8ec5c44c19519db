// The bow–string module: strictly passive at every step, stable for sharp curves and light
// strings, sticks when it should and slides at μd·N when the bow moves fast.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "archet/builders/bowed_string.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/compiled_model.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

// A wandering gesture: random walks on both axes, with sudden stops and reversals.
Gesture random_gesture(unsigned seed, double seconds) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> step(-0.04, 0.04), press(-0.0005, 0.005);
    std::vector<GestureKeyframe> frames;
    double x = 0;
    for (double t = 0; t <= seconds; t += 0.05) {
        frames.push_back({t, x, press(random)});
        x += step(random);
    }
    return Gesture("random", frames);
}

void run_and_check_passivity(Model model, unsigned seed) {
    validate_model(model);
    Simulation sim(compile(model));
    const Gesture g = random_gesture(seed, 2.0);
    sim.set_gesture_track(&g);
    const double e0 = sim.stored_energy();
    int sticking = 0, slipping = 0;
    double max_stored = 0;
    const auto& level = sim.model().levels[0];
    const auto bow_slot = sim.model().mat_slots.at(model.find_lia("friction")->from);
    const auto string_slot = sim.model().mat_slots.at(model.find_lia("friction")->to);
    auto relative = [&](int buffer) {  // bow minus string motion over a step, from positions
        const int s = (level.current + buffer) % 3;
        const int p = (level.current + buffer + 2) % 3;
        return (level.buffer[s][bow_slot.index] - level.buffer[p][bow_slot.index]) -
               (level.buffer[s][string_slot.index] - level.buffer[p][string_slot.index]);
    };
    for (int i = 0; i < 96000; ++i) {
        sim.step();
        const auto& bow = sim.model().bows[0];
        // The energy the friction took from the pair over the step, F·(u+ + u−)/2, from the
        // positions the scheme produced; and the module's own account of it.
        const double u_next = relative(0), u_prev = relative(2);
        const double taken = 0.5 * bow.friction * (u_next + u_prev);
        // Differences of positions carry rounding of the positions themselves.
        const double rounding =
            1e-14 * std::abs(bow.friction) *
            (std::abs(sim.position(bow_slot)) + std::abs(sim.position(string_slot)));
        ASSERT_GE(taken, -rounding) << "friction created energy at step " << i;
        ASSERT_GE(bow.dissipated, 0.0);
        ASSERT_NEAR(bow.dissipated, taken, rounding + 1e-9 * std::abs(taken));
        ASSERT_TRUE(std::isfinite(bow.friction));
        ASSERT_LE(std::abs(bow.friction), bow.mu_s * bow.normal * (1 + 1e-12));
        if (bow.normal > 0) (bow.sticking ? sticking : slipping)++;
        max_stored = std::max(max_stored, sim.stored_energy());
    }
    EXPECT_GT(sticking, 1000);
    EXPECT_GT(slipping, 1000);
    // Nothing in the model can hold more than it started with plus what the hand put in,
    // give or take the explicit dampers' per-step bookkeeping.
    EXPECT_LE(sim.stored_energy(), e0 + sim.hand_work() + 1e-9);
    EXPECT_TRUE(std::isfinite(max_stored));
}

TEST(Friction, PassiveAtEveryStepOnTheShippedString) {
    BowedStringOptions o;
    o.pitch = 220;
    run_and_check_passivity(build_bowed_string(o), 1);
}

TEST(Friction, StableAndPassiveWithASharpCurveAndALightString) {
    BowedStringOptions o;
    o.pitch = 440;
    o.linear_density = 1e-5;                  // a 72 times lighter string: tiny masses at 48 kHz
    o.mu_s = 1.5, o.mu_d = 0.1, o.v0 = 1e-4;  // a near-vertical stick peak
    o.buffer_stiffness = 1e5;
    Model model = build_bowed_string(o);
    // An explicit friction from the previous velocity would need Z_n = N·μ'·T/m < 2; here it
    // is many orders beyond.
    const double m = model.find_mat("s3")->mass;
    const double slope = 0.1 * (o.mu_s - o.mu_d) / o.v0;  // N·μ' at the stick peak, N ≈ 0.1
    ASSERT_GT(slope / 48000 / m, 100.0);
    run_and_check_passivity(model, 2);
}

// A bow mass and a string mass, nothing else; the press mass sits 1 mm into the buffer.
Model bow_on_mass(double bow_velocity, double string_mass, double buffer_stiffness, double v0) {
    Model model;
    model.mats = {test::mass("bow", 1.0), test::mass("string", string_mass),
                  test::mass("press", 0.01), test::fixed("surface")};
    model.mats[0].velocity = bow_velocity;
    model.mats[2].position = 1e-3;
    Lia f;
    f.id = "friction", f.kind = LiaKind::BowFriction, f.from = "bow", f.to = "string",
    f.press = "press", f.surface = "surface", f.stiffness = buffer_stiffness, f.mu_static = 0.8,
    f.mu_dynamic = 0.3, f.v0 = v0;
    model.lias.push_back(f);
    validate_model(model);
    return model;
}

TEST(Friction, SlidesAtTheDynamicCoefficientWhenTheBowIsFast) {
    // A bow pulled fast across a very heavy string mass: v_rel ≫ v0, so |F| → μd·N.
    Simulation sim(compile(bow_on_mass(5.0, 1e3, 100, 0.01)));
    sim.step();
    const auto& bow = sim.model().bows[0];
    ASSERT_NEAR(bow.normal, 0.1, 1e-12);
    const double v = bow.slip_velocity;
    EXPECT_NEAR(std::abs(bow.friction), bow.normal * (0.3 + 0.5 * 0.01 / (0.01 + v)),
                1e-3 * bow.normal);
    EXPECT_GT(bow.friction, 0);  // drags the string along the bow
    EXPECT_FALSE(bow.sticking);
}

TEST(Friction, SticksWhenTheNeededForceIsBelowTheStaticLimit) {
    // A slow bow on a light free mass: friction carries the mass along exactly.
    Simulation sim(compile(bow_on_mass(0.05, 1e-3, 1000, 0.1)));
    for (int i = 0; i < 100; ++i) sim.step();
    const auto& bow = sim.model().bows[0];
    EXPECT_TRUE(bow.sticking);
    EXPECT_NEAR(bow.slip_velocity, 0.0, 1e-12);
    EXPECT_NEAR(sim.velocity(sim.model().mat_slots.at("string")),
                sim.velocity(sim.model().mat_slots.at("bow")), 1e-12);
}

std::uint64_t bits(double value) {
    return std::bit_cast<std::uint64_t>(value);
}

// Revision 4 multiplies by the reciprocals of T and of the masses' response where the solve
// divided: the same physics, other last bits. A take of an older revision re-renders with the
// divisions (compute_as_of()), and so does a simulation that continues from one.
TEST(Friction, Revision4sReciprocalsChangeOnlyTheLastBits) {
    BowedStringOptions o;
    o.pitch = 220;
    const Model model = build_bowed_string(o);
    Simulation now(compile(model)), divided(compile(model));
    divided.compute_as_of(3);
    now.set_gesture_track(&*model.gesture);
    divided.set_gesture_track(&*model.gesture);
    int differing = 0, sticking = 0, slipping = 0;
    double largest = 0, largest_difference = 0;
    for (int i = 0; i < 24000; ++i) {
        now.step(), divided.step();
        const CompiledBow &a = now.model().bows[0], &b = divided.model().bows[0];
        differing += bits(a.friction) != bits(b.friction);
        sticking += a.sticking && a.normal > 0;
        slipping += !a.sticking && a.normal > 0;
        largest = std::max(largest, std::abs(b.friction));
        largest_difference = std::max(largest_difference, std::abs(a.friction - b.friction));
    }
    ASSERT_GT(sticking, 1000) << "the bow plays: it sticks";
    ASSERT_GT(slipping, 1000) << "and slips";
    EXPECT_GT(differing, 100) << "the two revisions compute the friction differently";
    EXPECT_LT(largest_difference, 1e-9 * largest) << "by rounding only";

    Simulation continued(compile(model));
    continued.set_gesture_track(&*model.gesture);
    std::vector<double> scratch(continued.state_size());
    ASSERT_TRUE(continued.continue_from(divided, scratch));
    for (int i = 0; i < 4800; ++i) {
        divided.step(), continued.step();
        ASSERT_EQ(bits(continued.model().bows[0].friction), bits(divided.model().bows[0].friction))
            << "step " << i << ": the continued simulation divides too";
    }
}

TEST(Friction, NoContactNoFriction) {
    BowedStringOptions o;
    Model model = build_bowed_string(o);
    model.gesture = Gesture("lifted", {{0, 0, -0.002}, {1, 0.1, -0.002}});
    Simulation sim(compile(model));
    for (int i = 0; i < 48000; ++i) {
        sim.step();
        ASSERT_EQ(sim.model().bows[0].normal, 0.0);
        ASSERT_EQ(sim.model().bows[0].friction, 0.0);
    }
}

}  // namespace
}  // namespace archet
