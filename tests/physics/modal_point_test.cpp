// A modal point's position, the sum the step makes after every force on a modal body
// (physics/modal_point_position.hpp): its terms in order up to eight, in eight interleaved
// partial sums added in a fixed tree beyond (revision 3 of the scheme), to the same bits
// wherever its modes lie in storage.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "archet/builders/bowed_string.hpp"
#include "archet/common/scheme_revision.hpp"
#include "archet/model/gesture.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/model_variants.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/modal_point_position.hpp"
#include "archet/physics/scheme_changes.hpp"
#include "archet/physics/simulation.hpp"
#include "second_bow.hpp"

namespace archet {
namespace {

// A point of n terms over storage 1 … n, and positions there: its modes in storage order
// (read as one run) or shuffled (read one by one), the same term for each k either way.
struct PointAndStorage {
    CompiledModalPoint point;
    std::vector<double> x;
};

PointAndStorage random_point(std::size_t n, bool in_order, std::mt19937_64& random) {
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    PointAndStorage p;
    p.x.assign(n + 2, 0.0);
    std::vector<int> where(n);
    std::iota(where.begin(), where.end(), 1);
    if (!in_order) std::shuffle(where.begin(), where.end(), random);
    for (std::size_t k = 0; k < n; ++k) {
        p.point.modes.push_back(where[k]);
        p.point.weights.push_back(value(random));
        p.x[where[k]] = value(random) * std::pow(10.0, static_cast<int>(k % 7) - 3);
    }
    p.point.first_mode = in_order ? 1 : -1;
    return p;
}

double term(const PointAndStorage& p, std::size_t k) {
    return p.point.weights[k] * p.x[p.point.modes[k]];
}

std::uint64_t bits(double v) {
    return std::bit_cast<std::uint64_t>(v);
}

constexpr ChainBuild kBuilds[] = {ChainBuild::Plain, ChainBuild::Avx2, ChainBuild::Avx512};

TEST(ModalPoint, UpToEightTermsAddInOrder) {
    std::mt19937_64 random(1);
    for (std::size_t n = 1; n <= kModalSumLanes; ++n)
        for (bool in_order : {true, false})
            for (int trial = 0; trial < 100; ++trial) {
                const PointAndStorage p = random_point(n, in_order, random);
                double expected = 0;
                for (std::size_t k = 0; k < n; ++k) expected += term(p, k);
                EXPECT_EQ(bits(modal_point_position(p.point, p.x.data())), bits(expected))
                    << n << " terms";
            }
}

TEST(ModalPoint, LongerSumsAddEightInterleavedPartialSumsInAFixedTree) {
    std::mt19937_64 random(2);
    for (std::size_t n : {9, 10, 11, 12, 13, 14, 15, 16, 17, 23, 60, 61, 62, 200})
        for (int trial = 0; trial < 100; ++trial) {
            const PointAndStorage in_order = random_point(n, true, random);
            double lane[8] = {};
            long double exact = 0, magnitude = 0;
            for (std::size_t k = 0; k < n; ++k) {
                lane[k % 8] += term(in_order, k);
                exact += static_cast<long double>(in_order.point.weights[k]) *
                         in_order.x[in_order.point.modes[k]];
                magnitude += std::abs(term(in_order, k));
            }
            const double expected = ((lane[0] + lane[1]) + (lane[2] + lane[3])) +
                                    ((lane[4] + lane[5]) + (lane[6] + lane[7]));
            const double sum = modal_point_position(in_order.point, in_order.x.data());
            ASSERT_EQ(bits(sum), bits(expected)) << n << " terms";
            // Each build of the run's sum (modal_kernel.cpp) that this CPU runs: the same bits.
            for (ChainBuild build : kBuilds) {
                if (!chain_build_runs_here(build)) continue;
                EXPECT_EQ(bits(modal_run_sum(in_order.point.weights.data(), n,
                                             in_order.x.data() + 1, build)),
                          bits(expected))
                    << chain_build_name(build) << ", " << n << " terms";
            }
            // A sum, whatever its order: within rounding of the exact one.
            EXPECT_LE(std::abs(static_cast<long double>(sum) - exact),
                      static_cast<long double>(n) * 0x1p-52L * magnitude);

            // The same terms with the modes shuffled in storage: the same bits.
            PointAndStorage shuffled = in_order;
            std::vector<int> where(n);
            std::iota(where.begin(), where.end(), 1);
            std::shuffle(where.begin(), where.end(), random);
            std::fill(shuffled.x.begin(), shuffled.x.end(), 0.0);
            for (std::size_t k = 0; k < n; ++k) {
                shuffled.point.modes[k] = where[k];
                shuffled.x[where[k]] = in_order.x[in_order.point.modes[k]];
            }
            shuffled.point.first_mode = -1;
            EXPECT_EQ(bits(modal_point_position(shuffled.point, shuffled.x.data())),
                      bits(expected));
        }
}

TEST(ModalPoint, AForceMovesEachModeByItsShareWhereverTheModesLie) {
    std::mt19937_64 random(3);
    // Tails of every length the builds leave after their whole vectors.
    for (std::size_t n : {1, 3, 8, 9, 10, 11, 13, 15, 60}) {
        const PointAndStorage in_order = random_point(n, true, random);
        PointAndStorage shuffled = random_point(n, false, random);
        shuffled.point.weights = in_order.point.weights;
        std::vector<double> coeff(n + 2), coeff_shuffled(n + 2);
        // Positions as small as the moves, so that every bit of a move shows in the sum.
        std::vector<double> moved(n + 2, 1e-7), moved_shuffled(n + 2, 1e-7);
        for (std::size_t k = 0; k < n; ++k) {
            coeff[in_order.point.modes[k]] = 1e-6 * static_cast<double>(k + 1);
            coeff_shuffled[shuffled.point.modes[k]] = coeff[in_order.point.modes[k]];
        }
        add_modal_force(in_order.point, coeff.data(), moved.data(), 0.3);
        add_modal_force(shuffled.point, coeff_shuffled.data(), moved_shuffled.data(), 0.3);
        for (std::size_t k = 0; k < n; ++k) {
            const double expected =
                1e-7 + coeff[in_order.point.modes[k]] * in_order.point.weights[k] * 0.3;
            EXPECT_EQ(bits(moved[in_order.point.modes[k]]), bits(expected));
            EXPECT_EQ(bits(moved_shuffled[shuffled.point.modes[k]]), bits(expected));
        }
        EXPECT_EQ(moved[0], 1e-7) << "nothing else moves";
        EXPECT_EQ(moved[n + 1], 1e-7);
        // Each build of the run's move (modal_kernel.cpp) that this CPU runs: the same bits.
        for (ChainBuild build : kBuilds) {
            if (!chain_build_runs_here(build)) continue;
            std::vector<double> by_build(n + 2, 1e-7);
            modal_run_move(in_order.point.weights.data(), n, coeff.data() + 1, by_build.data() + 1,
                           0.3, build);
            for (std::size_t s = 0; s < n + 2; ++s)
                EXPECT_EQ(bits(by_build[s]), bits(moved[s])) << chain_build_name(build);
        }
    }
}

BowedStringOptions modal_string() {
    BowedStringOptions o;
    o.pitch = 220;
    o.paper = true;
    o.masses = 60;
    o.structure = Structure::Modal;
    return o;
}

// The compiler reads a point's modes as one run when they lie in order (a modal string's do),
// and a whole bowed stroke plays to the same bits as reading them one by one.
TEST(ModalPoint, AModalStringReadsItsModesAsOneRunToTheSameBits) {
    const CompiledModel compiled = compile(build_bowed_string(modal_string()));
    CompiledModel one_by_one = compiled;
    int long_points = 0;
    for (auto& lv : one_by_one.levels)
        for (auto& p : lv.modal_points) {
            ASSERT_GE(p.first_mode, 0) << "a modal string's modes lie in order";
            for (std::size_t k = 0; k < p.modes.size(); ++k)
                ASSERT_EQ(p.modes[k], p.first_mode + static_cast<int>(k));
            long_points += p.modes.size() > kModalSumLanes;
            p.first_mode = -1;
        }
    EXPECT_EQ(long_points, 3) << "both ends and the bowed point, one term per mode";
    Simulation as_run(compiled), as_indexed(std::move(one_by_one));
    double loudest = 0;
    for (int i = 0; i < 24000; ++i) {
        as_run.step(), as_indexed.step();
        ASSERT_EQ(bits(as_run.output()), bits(as_indexed.output())) << "sample " << i;
        loudest = std::max(loudest, std::abs(as_run.output()));
    }
    EXPECT_GT(loudest, 1e-3) << "it was bowed";
}

// A simulation continued from another's state (the engine's swap to a recompiled model) puts
// its modal points where their modes put them, to the bit: it then plays on as the other does.
TEST(ModalPoint, AContinuedModalStringPlaysOnToTheSameBits) {
    const CompiledModel compiled = compile(build_bowed_string(modal_string()));
    Simulation played(compiled), continued(compiled);
    for (int i = 0; i < 9600; ++i) played.step();
    std::vector<double> scratch(played.state_size());
    ASSERT_TRUE(continued.continue_from(played, scratch));
    for (int i = 0; i < 9600; ++i) {
        played.step(), continued.step();
        ASSERT_EQ(bits(played.output()), bits(continued.output())) << "sample " << i;
    }
}

// Moving the bow of a playing string in modal form (the engine swaps in the moved model and
// continues from the played one's state): the string goes on from the motion it had, every
// point where its modes put it, whether the bow's point changed (a hair-wide bow: a point the
// step did not move before) or its contact's mix of the points there (a bow with a width).
TEST(ModalPoint, AModalStringsBowMovedWhilePlayingGoesOnFromItsMotion) {
    for (bool paper : {true, false}) {
        BowedStringOptions o = modal_string();
        o.paper = paper, o.masses = paper ? 60 : 0, o.pitch = paper ? 220 : 440;
        const Model model = build_bowed_string(o);
        Model moved = model;
        set_variant_parameter(moved, "bow.position", 0.25);
        Simulation played(compile(model)), continued(compile(moved));
        for (int i = 0; i < 9600; ++i) played.step();
        std::vector<double> scratch(played.state_size());
        ASSERT_TRUE(continued.continue_from(played, scratch));
        const std::string what = paper ? "hair-wide bow" : "bow with a width";
        const std::string bowed = moved.find_lia("friction")->bowed_string();
        if (paper)
            EXPECT_NE(bowed, model.find_lia("friction")->bowed_string()) << "another point";
        else
            EXPECT_NE(moved.find_mat(bowed)->weights, model.find_mat(bowed)->weights)
                << "another mix";
        double peak = 0, apart = 0;
        for (const Mat& m : model.mats) {
            if (m.kind == MatKind::Gesture || m.id == bowed) continue;
            const double x = played.position(played.model().mat_slots.at(m.id));
            peak = std::max(peak, std::abs(x));
            apart = std::max(
                apart, std::abs(continued.position(continued.model().mat_slots.at(m.id)) - x));
        }
        EXPECT_GT(peak, 1e-6) << what << ": it was bowed";
        EXPECT_LE(apart, 1e-12 * peak) << what;
        // The bow's point (or contact), moved: where its modes put it now, in the step's own
        // store and in x[n−1] as well.
        const MatSlot contact = continued.model().mat_slots.at(bowed);
        const CompiledLevel& audio = continued.model().levels[contact.level];
        double sum = 0, sum_prev = 0;
        const Mat& point = *moved.find_mat(bowed);
        for (std::size_t k = 0; k < point.modes.size(); ++k) {
            const int mode = continued.model().mat_slots.at(point.modes[k]).index;
            sum += point.weights[k] * audio.x()[mode];
            sum_prev += point.weights[k] * audio.x_prev()[mode];
        }
        EXPECT_NEAR(audio.x()[contact.index], sum, 1e-12 * peak) << what;
        EXPECT_NEAR(audio.x_prev()[contact.index], sum_prev, 1e-12 * peak) << what;
        for (int i = 0; i < 4800; ++i) continued.step();
        EXPECT_TRUE(std::isfinite(continued.output())) << what;
    }
}

// A take of an older revision re-renders to the byte unless its model computes differently
// now: the modal string's long points do since revision 3; the shipped string's (a bridge on
// six body modes, a bow over three masses) do not, nor does its bow since revision 4 (a take
// re-renders with the friction's divisions). Since revision 6 the modal string's points that
// nothing reads are not counted in the grounds' choice: its grounds join the chain loop.
TEST(ModalPoint, OnlyPointsOfMoreThanEightTermsComputeDifferentlySinceRevision3) {
    static_assert(kSchemeRevision == 6);
    const Model modal_model = build_bowed_string(modal_string());
    const CompiledModel modal = compile(modal_model);
    EXPECT_EQ(scheme_change_since(modal, 2), SchemeChange::Rounding);
    EXPECT_EQ(scheme_change_since(modal, 5), SchemeChange::Rounding) << "its grounds, since 6";
    EXPECT_EQ(scheme_change_since(modal, 6), SchemeChange::None);
    Model read_points_alone = modal_model;  // as the builder made it before revision 6
    std::erase_if(read_points_alone.mats, [](const Mat& m) {
        return m.kind == MatKind::ModalPoint && m.id != "s1" && m.id != "s7" && m.id != "s60";
    });
    EXPECT_EQ(scheme_change_since(compile(read_points_alone), 3), SchemeChange::None);
    BowedStringOptions shipped;
    shipped.pitch = 220;
    const CompiledModel string = compile(build_bowed_string(shipped));
    int points = 0;
    for (const auto& lv : string.levels)
        for (const auto& p : lv.modal_points) {
            EXPECT_LE(p.modes.size(), kModalSumLanes);
            ++points;
        }
    EXPECT_EQ(points, 2);
    EXPECT_EQ(scheme_change_since(string, 4), SchemeChange::None);
    EXPECT_EQ(scheme_change_since(string, 3), SchemeChange::None);
    EXPECT_EQ(scheme_change_since(string, 2), SchemeChange::None);
    EXPECT_EQ(scheme_change_since(string, 1), SchemeChange::Rounding) << "its grounds, since 2";
}

// Plays `model` along its own stroke and, after every step, holds each modal point to the bits
// of the sum of its modes: where a push left one behind, nothing after it in the step moved it.
void expect_points_where_their_modes_are(const Model& model, int ticks) {
    ASSERT_TRUE(model.gesture);
    Simulation sim(compile(model));
    sim.set_gesture_track(&*model.gesture);
    double loudest = 0;
    for (int i = 0; i < ticks; ++i) {
        sim.step();
        for (const CompiledLevel& lv : sim.model().levels)
            for (const CompiledModalPoint& p : lv.modal_points)
                ASSERT_EQ(bits(lv.x()[p.index]), bits(modal_point_position(p, lv.x())))
                    << "a point behind its modes after step " << i;
        loudest = std::max(loudest, std::abs(sim.output()));
    }
    EXPECT_GT(loudest, 1e-3) << "it was bowed";
}

std::vector<int> moving_with(const CompiledLevel& lv, int storage) {
    return lv.modal_points[lv.modal_point_of[storage]].moving_with;
}

// A force on a modal point moves the points that share its modes, the others being where
// their modes are already: the shipped string (the bow's hair on three masses, the bridge on
// six body modes) and a modal string (every point on every mode).
TEST(ModalPoint, AForceMovesThePointsSharingItsModes) {
    BowedStringOptions o;
    o.pitch = 220;
    const Model shipped = build_bowed_string(o);
    const CompiledModel compiled = compile(shipped);
    const CompiledLevel& audio = compiled.levels[0];
    const int hair = compiled.bows[0].string, bridge = compiled.mat_slots.at("bridge").index;
    EXPECT_EQ(moving_with(audio, hair), std::vector<int>{audio.modal_point_of[hair]});
    EXPECT_EQ(moving_with(audio, bridge), std::vector<int>{audio.modal_point_of[bridge]});
    expect_points_where_their_modes_are(shipped, 48000);
    const Model modal = build_bowed_string(modal_string());
    const CompiledModel modal_compiled = compile(modal);
    for (const CompiledModalPoint& p : modal_compiled.levels[0].modal_points)
        EXPECT_EQ(p.moving_with, (std::vector<int>{0, 1, 2}));
    expect_points_where_their_modes_are(modal, 24000);
}

// A finger's push on a plain mass a point reads moves that point (Simulation::push_pair()): on
// the shipped fingered string, and with the finger halfway between the bridge and s1 where a
// point of its own reads s1 alone and the hair reads s2–s4 (nothing else moves that point).
TEST(ModalPoint, AFingersPushMovesThePointsReadingItsMass) {
    BowedStringOptions o;
    o.pitch = 220, o.finger = true, o.finger_position = 0.75;
    expect_points_where_their_modes_are(build_bowed_string(o), 24000);
    o.masses = 63;
    o.finger_position = 1.0 / 128;
    Model at_the_bridge = build_bowed_string(o);
    at_the_bridge.find_mat("bow_contact")->modes = {"s2", "s3", "s4"};
    Mat on_s1;
    on_s1.id = "on_s1", on_s1.kind = MatKind::ModalPoint, on_s1.rate = "audio";
    on_s1.modes = {"s1"}, on_s1.weights = {1.0};
    at_the_bridge.mats.push_back(on_s1);
    validate_model(at_the_bridge);
    expect_points_where_their_modes_are(at_the_bridge, 24000);
}

// A bow's push on a plain mass a point reads moves that point: a bow on the hair's middle mass,
// alone and followed by a second bow on the bridge, which reads the hair's modes after it.
TEST(ModalPoint, ABowsPushMovesThePointsReadingItsMass) {
    BowedStringOptions o;
    o.pitch = 220;
    Model on_a_mode = build_bowed_string(o);
    Lia* friction = on_a_mode.find_lia("friction");
    const Mat* hair = on_a_mode.find_mat(friction->bowed_string());
    ASSERT_EQ(hair->kind, MatKind::ModalPoint);
    friction->to = hair->modes[1];  // the middle mass under the hair, which the hair reads
    validate_model(on_a_mode);
    expect_points_where_their_modes_are(on_a_mode, 24000);
    const CompiledModel compiled = compile(on_a_mode);
    EXPECT_EQ(scheme_change_since(compiled, 4), SchemeChange::Fix);
    EXPECT_EQ(scheme_change_since(compiled, 5), SchemeChange::None);
    test::add_second_bow(on_a_mode, "bridge");
    validate_model(on_a_mode);
    expect_points_where_their_modes_are(on_a_mode, 24000);
}

}  // namespace
}  // namespace archet
