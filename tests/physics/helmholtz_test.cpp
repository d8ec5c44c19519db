// With a steady bow the shipped strings fall into Helmholtz motion: one slip per period at
// the period of the first mode, the slip lasting about β of it, the string moving with the
// bow while sticking and back at about −v_b(1−β)/β while slipping (physics.md §4).

#include <gtest/gtest.h>

#include <cmath>

#include "archet/analysis/bowing_analysis.hpp"
#include "archet/analysis/discrete_modes.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/linear_system.hpp"
#include "archet/physics/compiled_model.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

struct Bowing {
    std::vector<double> slip, string_velocity, bow_velocity;
    double beta = 0, pitch = 0, fs = 0;
};

std::size_t probe_index(const Model& m, const std::string& id) {
    for (std::size_t i = 0; i < m.probes.size(); ++i)
        if (m.probes[i].id == id) return i;
    throw std::runtime_error("no probe " + id);
}

Bowing bow(const Model& model, double seconds) {
    Bowing b;
    Simulation sim(compile(model));
    b.fs = sim.sample_rate();
    const auto modes = discrete_modes(sounding_part(model));
    for (const auto& m : modes)  // the string's first mode: the first above the bridges'
        if (m.t60 > 0.5) {
            b.pitch = m.frequency;
            break;
        }
    const auto& f = *model.find_lia("friction");
    int n = 0;
    for (const auto& m : model.mats)
        n += m.id.size() > 1 && m.id[0] == 's' && std::isdigit(m.id[1]);
    b.beta = std::stod(f.to.substr(1)) / (n + 1);
    const auto slip = probe_index(model, "slip_v"), sv = probe_index(model, "bow_point_v"),
               bv = probe_index(model, "bow_v");
    for (int i = 0; i < seconds * b.fs; ++i) {
        sim.step();
        b.slip.push_back(sim.probe(slip));
        b.string_velocity.push_back(sim.probe(sv));
        b.bow_velocity.push_back(sim.probe(bv));
    }
    return b;
}

class ShippedString : public ::testing::TestWithParam<int> {};

TEST_P(ShippedString, SteadyBowGivesHelmholtzMotion) {
    const int pitch = GetParam();
    const Model model =
        load_model_file(test::resource("models/bowed-string-" + std::to_string(pitch) + ".json"));
    ASSERT_TRUE(model.gesture);
    EXPECT_EQ(*model.gesture, load_gesture_file(test::resource("gestures/steady-bow.json")));
    // The steady stroke lasts until 2.6 s; the homogeneous 110 Hz string, slowest to settle,
    // is in Helmholtz motion from about 1.3 s.
    const Bowing b = bow(model, 2.6);
    EXPECT_NEAR(b.pitch, pitch, 1e-6) << "the shipped string is tuned to its pitch";
    const auto a = analyse_bowing(b.slip, b.fs, b.pitch, static_cast<std::size_t>(1.5 * b.fs),
                                  static_cast<std::size_t>(2.55 * b.fs));
    EXPECT_NEAR(a.slips_per_period, 1.0, 0.03) << "one slip per period";
    EXPECT_LT(a.period_spread, 0.05) << "a steady period";
    // The period is the first mode's, a little flat: the homogeneous chain's partials are flat.
    EXPECT_LT(a.pitch_cents, 5.0);
    EXPECT_GT(a.pitch_cents, -30.0);
    EXPECT_GT(a.slip_share, 0.8 * b.beta);
    EXPECT_LT(a.slip_share, 2.0 * b.beta);
    EXPECT_TRUE(a.helmholtz());

    // String velocity at the bow: the bow's while sticking, about −v_b(1−β)/β while slipping.
    double stick_sum = 0, slip_min = 0;
    int stick_count = 0;
    for (std::size_t i = static_cast<std::size_t>(1.5 * b.fs);
         i < static_cast<std::size_t>(2.55 * b.fs); ++i) {
        if (b.slip[i] == 0.0) stick_sum += b.string_velocity[i] - b.bow_velocity[i], ++stick_count;
        slip_min = std::min(slip_min, b.string_velocity[i]);
    }
    EXPECT_NEAR(stick_sum / stick_count, 0.0, 1e-12);
    const double vb = 0.1;
    EXPECT_NEAR(slip_min / (-vb * (1 - b.beta) / b.beta), 1.0, 0.3);
}

INSTANTIATE_TEST_SUITE_P(PaperPitches, ShippedString, ::testing::Values(110, 220, 440, 880));

TEST(Helmholtz, SlipShareGrowsWithBowDistanceFromTheBridge) {
    double previous = 0;
    for (double beta : {0.1, 0.15, 0.2, 0.25}) {
        BowedStringOptions o;
        o.pitch = 220, o.bow_position = beta;
        const Bowing b = bow(build_bowed_string(o), 2.0);
        const auto a = analyse_bowing(b.slip, b.fs, b.pitch, static_cast<std::size_t>(1.0 * b.fs),
                                      static_cast<std::size_t>(1.9 * b.fs));
        EXPECT_TRUE(a.helmholtz())
            << "beta " << beta << ": " << a.slips_per_period << " slips per period";
        EXPECT_GT(a.slip_share, previous) << "beta " << beta;
        previous = a.slip_share;
    }
}

TEST(Helmholtz, TooLittleForceGivesSeveralSlipsPerPeriod) {
    // Below Schelleng's minimum bow force the string slips more than once per period.
    Model model = load_model_file(test::resource("models/bowed-string-110.json"));
    model.find_mat("hand_press")->position_scale = 0.3;
    const Bowing b = bow(model, 2.0);
    const auto a = analyse_bowing(b.slip, b.fs, b.pitch, static_cast<std::size_t>(1.0 * b.fs),
                                  static_cast<std::size_t>(1.9 * b.fs));
    EXPECT_GT(a.slips_per_period, 1.5);
    EXPECT_FALSE(a.helmholtz());
}

}  // namespace
}  // namespace archet
