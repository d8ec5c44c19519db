// Live parameter changes glide instead of stepping; every parameter reads back what was set.

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include "archet/builders/bowed_string.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/parameter_smoother.hpp"

namespace archet {
namespace {

TEST(ParameterSmoother, GlidesLinearlyToTheTarget) {
    Simulation sim(compile(build_bowed_string({})));
    const auto slot = sim.model().resolve_parameter({"friction", "mu_s"});
    ParameterSmoother smoother;
    smoother.glide(sim, slot, 0.9, 480);
    double previous = sim.read_slot(slot);
    EXPECT_EQ(previous, 0.8);
    for (int i = 0; i < 480; ++i) {
        smoother.advance(sim);
        const double now = sim.read_slot(slot);
        EXPECT_NEAR(now - previous, 0.1 / 480, 1e-12) << "step " << i;
        previous = now;
        sim.step();
    }
    EXPECT_EQ(sim.read_slot(slot), 0.9);
    EXPECT_EQ(smoother.active(), 0u);
}

TEST(ParameterSmoother, RetargetsFromWhereItIsAndSetsAtOnceWhenFull) {
    Simulation sim(compile(build_bowed_string({})));
    const auto slot = sim.model().resolve_parameter({"k3", "stiffness"});
    const double start = sim.read_slot(slot);
    ParameterSmoother smoother;
    smoother.glide(sim, slot, 2 * start, 100);
    for (int i = 0; i < 50; ++i) smoother.advance(sim);
    EXPECT_NEAR(sim.read_slot(slot), 1.5 * start, 1e-9 * start);
    smoother.glide(sim, slot, start, 10);  // back, from halfway
    EXPECT_EQ(smoother.active(), 1u);
    for (int i = 0; i < 10; ++i) smoother.advance(sim);
    EXPECT_NEAR(sim.read_slot(slot), start, 1e-9 * start);
    for (int i = 0; i < static_cast<int>(ParameterSmoother::kCapacity); ++i)
        smoother.glide(sim, sim.model().resolve_parameter({"k" + std::to_string(i + 1), "damping"}),
                       1e-4, 100);
    const auto extra = sim.model().resolve_parameter({"k40", "damping"});
    smoother.glide(sim, extra, 2e-4, 100);
    EXPECT_EQ(sim.read_slot(extra), 2e-4) << "no room: set at once";
}

TEST(SimulationParameters, EveryKindReadsBackWhatWasSet) {
    const Model model = build_bowed_string({});
    Simulation sim(compile(model));
    for (const auto& [element, name] :
         std::vector<std::pair<std::string, std::string>>{{"s5", "mass"},
                                                          {"k3", "stiffness"},
                                                          {"k3", "damping"},
                                                          {"s5", "damping"},
                                                          {"nut", "stiffness"},
                                                          {"nut", "damping"},
                                                          {"body1", "stiffness"},
                                                          {"body2", "damping"},
                                                          {"bow_hold", "stiffness"},
                                                          {"bow_hold", "damping"},
                                                          {"friction", "buffer_stiffness"},
                                                          {"friction", "buffer_damping"},
                                                          {"friction", "mu_s"},
                                                          {"friction", "mu_d"},
                                                          {"friction", "v0"},
                                                          {"hand_slide", "position_scale"},
                                                          {"hand_press", "force_scale"},
                                                          {"surface", "position"}}) {
        const auto slot = sim.model().resolve_parameter({element, name});
        EXPECT_NEAR(sim.read_slot(slot), get_parameter(model, {element, name}),
                    1e-12 * std::abs(get_parameter(model, {element, name})))
            << element << "." << name;
        const double value = 0.37 * (get_parameter(model, {element, name}) + 1.0);
        sim.write_slot(slot, value);
        EXPECT_NEAR(sim.read_slot(slot), value, 1e-12 * std::abs(value)) << element << "." << name;
    }
}

// A string whose masses have grounds takes them in its update's coefficients (fold_ground()):
// a mass or a ground set while running, or loaded with a saved state, must play exactly as if
// the model had been compiled with it. (The string's masses have a damper to their rest point
// and no spring; the bridges have both.) So must a chain link's, and a mass's in the middle of
// the run of alike MATs whose coefficients the chain loop broadcasts.
TEST(SimulationParameters, ACoefficientSetWhilePlayingPlaysAsIfCompiledWithIt) {
    const Model model = build_bowed_string({});
    struct Change {
        std::string element, name;
        double value;
        bool mid_run = false;  ///< well inside the run the chain loop broadcasts
    };
    const double nut_k = get_parameter(model, {"nut", "stiffness"});
    for (const Change& c : std::vector<Change>{
             {"s5", "mass", 1.7 * get_parameter(model, {"s5", "mass"})},
             {"s5", "stiffness", 2000.0},
             {"s5", "damping", 1.7 * get_parameter(model, {"s5", "damping"})},
             {"nut", "stiffness", 1.7 * nut_k},
             {"nut", "damping", 1.7 * get_parameter(model, {"nut", "damping"})},
             // Mid-string, where the chain loop broadcasts the coefficients
             // the MATs share (uniform_span.hpp).
             {"s30", "mass", 1.7 * get_parameter(model, {"s30", "mass"}), true},
             {"k30", "stiffness", 0.6 * get_parameter(model, {"k30", "stiffness"}), true},
             {"k30", "damping", 1.7 * get_parameter(model, {"k30", "damping"}), true},
             {"k30", "length", 1e-4, true}}) {
        const std::string what = c.element + "." + c.name;
        ASSERT_NE(c.value, get_parameter(model, {c.element, c.name})) << what;
        Model changed = model;
        set_parameter(changed, {c.element, c.name}, c.value);
        Simulation set_live(compile(model)), compiled(compile(changed));
        const ParameterSlot slot = set_live.model().resolve_parameter({c.element, c.name});
        const UniformRuns& runs = set_live.model().levels[slot.level].uniform;
        auto in_a_run = [&](int s) {
            return std::any_of(runs.all().begin(), runs.all().end(),
                               [s](const UniformSpan& r) { return r.first <= s && s <= r.last; });
        };
        if (c.mid_run) {
            ASSERT_TRUE(in_a_run(slot.index - 8) && in_a_run(slot.index + 8));
            ASSERT_TRUE(in_a_run(slot.index));
        }
        set_live.write_slot(slot, c.value);
        if (c.mid_run) {
            EXPECT_FALSE(in_a_run(slot.index)) << what;
            EXPECT_TRUE(in_a_run(slot.index - 8) && in_a_run(slot.index + 8))
                << what << ": both sides of the changed MAT stay runs";
        }
        for (int i = 0; i < 4800; ++i) {
            set_live.step(), compiled.step();
            ASSERT_EQ(set_live.output(), compiled.output()) << what << " step " << i;
        }
        // The same change carried by a saved state into a simulation compiled without it.
        std::vector<double> state(set_live.state_size());
        set_live.save_state(state.data());
        Simulation resumed(compile(model));
        resumed.load_state(state.data());
        for (int i = 0; i < 4800; ++i) {
            set_live.step(), resumed.step();
            ASSERT_EQ(set_live.output(), resumed.output()) << what << " resumed " << i;
        }
    }
}

// A knob that moves every damper of a string glides each of them; each write splits the run
// the chain loop broadcasts at its MAT, and once the last glide ends the MATs, alike
// again, are one run again.
TEST(ParameterSmoother, WhenTheLastGlideEndsTheRunOfAlikeMatsIsWholeAgain) {
    BowedStringOptions o;
    o.masses = 30;
    const Model model = build_bowed_string(o);
    Simulation sim(compile(model));
    const UniformRuns before = sim.model().levels.front().uniform;
    ASSERT_EQ(before.count(), 1);
    ASSERT_GE(before[0].length(), 20);
    ParameterSmoother smoother;
    int glides = 0;
    for (const Lia& l : model.lias)
        if (l.id.size() > 1 && l.id[0] == 'k' && std::isdigit(l.id[1])) {
            const ParameterName damping{l.id, "damping"};
            smoother.glide(sim, sim.model().resolve_parameter(damping),
                           1.5 * get_parameter(model, damping), 48);
            ++glides;
        }
    ASSERT_GE(glides, 20);
    ASSERT_LE(static_cast<std::size_t>(glides), ParameterSmoother::kCapacity);
    for (int i = 0; i < 24; ++i) smoother.advance(sim), sim.step();
    const UniformRuns& now = sim.model().levels.front().uniform;
    EXPECT_EQ(now.count(), 0);  // split away while they glide
    while (smoother.active() > 0) smoother.advance(sim), sim.step();
    ASSERT_EQ(now.count(), 1);
    EXPECT_EQ(now[0].first, before[0].first);
    EXPECT_EQ(now[0].last, before[0].last);
    EXPECT_FALSE(now[0].shared == before[0].shared);  // the new damping
}

}  // namespace
}  // namespace archet
