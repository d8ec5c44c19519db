// The modal string: one damped oscillator per mode of the free chain, a modal point at each of
// its masses. Its partials are the chaplet's; bowed with the same gesture it plays the same
// sound and takes the same shape to round-off; the points nothing reads cost its step nothing.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/playability.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/model_variants.hpp"
#include "archet/model/string_points.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/simulation.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

// The full string (body, losses, hair-wide bow) or the paper's 60-mass chaplet.
Model build(Tuning tuning, Structure structure, double pitch = 220, bool paper = false) {
    BowedStringOptions o;
    o.pitch = pitch, o.tuning = tuning, o.structure = structure, o.paper = paper;
    return build_bowed_string(o);
}

class ModalString : public ::testing::TestWithParam<Tuning> {};

TEST_P(ModalString, PartialsMatchTheChapletsWithinACent) {
    const ModalAnalysis chain = analyse_modes(build(GetParam(), Structure::Chain));
    const ModalAnalysis modal = analyse_modes(build(GetParam(), Structure::Modal));
    ASSERT_EQ(chain.modes.size(), modal.modes.size());
    int compared = 0;
    for (std::size_t i = 0; i < chain.modes.size(); ++i) {
        EXPECT_EQ(chain.modes[i].partial, modal.modes[i].partial);
        EXPECT_NEAR(1200 * std::log2(modal.modes[i].frequency / chain.modes[i].frequency), 0.0,
                    1e-6);
        EXPECT_NEAR(modal.modes[i].t60 / chain.modes[i].t60, 1.0, 1e-6);
        compared += chain.modes[i].partial >= 1 && chain.modes[i].partial <= 10;
    }
    EXPECT_EQ(compared, 10);
}

TEST_P(ModalString, PlaysTheSameAsTheChaplet) {
    const Model chain_model = build(GetParam(), Structure::Chain);
    Model modal_model = build(GetParam(), Structure::Modal);
    // Each found its own stroke and gain; play both with the chain's.
    modal_model.gesture = chain_model.gesture, modal_model.output_gain = chain_model.output_gain;
    Simulation chain(compile(chain_model));
    Simulation modal(compile(modal_model));
    ASSERT_EQ(chain.probe_count(), modal.probe_count());
    double difference = 0, scale = 0;
    for (int i = 0; i < 48000; ++i) {
        chain.step(), modal.step();
        for (std::size_t p = 0; p < chain.probe_count(); ++p) {
            difference = std::max(difference, std::abs(chain.probe(p) - modal.probe(p)) /
                                                  (std::abs(chain.probe(p)) + 1e-3));
        }
        scale = std::max(scale, std::abs(chain.output()));
    }
    EXPECT_GT(scale, 0.05) << "it was bowed";
    EXPECT_LT(difference, 1e-6);
}

// Every mass of the chain has its point in the modal form, which is where the chaplet's mass
// is when both are bowed alike: the string's shape, drawn from either, is the same.
TEST_P(ModalString, EveryMassHasAPointThatMovesAsTheChapletsMassDoes) {
    const Model chain_model = build(GetParam(), Structure::Chain);
    Model modal_model = build(GetParam(), Structure::Modal);
    modal_model.gesture = chain_model.gesture, modal_model.output_gain = chain_model.output_gain;
    const std::vector<std::string> shape = string_points(chain_model);
    ASSERT_EQ(string_points(modal_model), shape) << "the bridge, s1…sN and the nut in both";
    // The bow is as wide as its hair: both strings have a contact point of their own (¼, ½, ¼
    // of the string at the bowed mass and beside it), centred on the same mass.
    const Lia* bow = chain_model.find_lia("friction");
    ASSERT_NE(bow, nullptr);
    const std::string centre = bowed_centre(chain_model, *bow);
    ASSERT_NE(centre, bow->bowed_string()) << "a contact point, not the mass";
    EXPECT_EQ(modal_model.find_lia("friction")->bowed_string(), bow->bowed_string());
    EXPECT_EQ(bowed_centre(modal_model, *modal_model.find_lia("friction")), centre);
    std::vector<std::string> points = shape;
    points.push_back(bow->bowed_string());
    Simulation chain(compile(chain_model));
    Simulation modal(compile(modal_model));
    double difference = 0, peak = 0;
    for (int i = 1; i <= 48000; ++i) {
        chain.step(), modal.step();
        if (i % 4800 != 0) continue;
        for (const std::string& id : points) {
            const MatSlot mass = chain.model().mat_slots.at(id);
            const double x = chain.position(mass), v = chain.velocity(mass);
            const MatSlot point = modal.model().mat_slots.at(id);
            difference = std::max(difference, std::abs(modal.position(point) - x));
            difference = std::max(difference, std::abs(modal.velocity(point) - v) / 48000);
            peak = std::max(peak, std::abs(x));
        }
    }
    EXPECT_GT(peak, 1e-5) << "the string was bowed";
    EXPECT_LT(difference, 1e-6 * peak);
}

INSTANTIATE_TEST_SUITE_P(Tunings, ModalString,
                         ::testing::Values(Tuning::Homogeneous, Tuning::Harmonic));

TEST(ModalString, FileRoundTripsAndNamesItsParts) {
    const Model model = build(Tuning::Homogeneous, Structure::Modal, 220, true);
    EXPECT_EQ(model.name, "bowed-string-220-modal-paper");
    const std::string text = format_model(model);
    EXPECT_EQ(format_model(parse_model(text)), text);
    const Mat* point = model.find_mat("s7");
    ASSERT_NE(point, nullptr);
    EXPECT_EQ(point->kind, MatKind::ModalPoint);
    EXPECT_EQ(point->modes.size(), 60u);
    EXPECT_NE(text.find("\"type\": \"modal_point\""), std::string::npos);
}

// The string's shape is the bowed string alone: a second point on the body's modes (a second
// string's bridge, say) shares modes with the bridge, not with the bowed string.
TEST(ModalString, TheShapeLeavesOutOtherPointsOfTheBody) {
    for (Structure structure : {Structure::Chain, Structure::Modal}) {
        Model model = build(Tuning::Homogeneous, structure, 220, false);
        const std::vector<std::string> shape = string_points(model);
        Mat other_bridge = *model.find_mat("bridge");  // a point on the body's modes
        other_bridge.id = "other_bridge";
        Mat other_string;
        other_string.id = "other_string", other_string.mass = 1e-4;
        Lia link;
        link.id = "other_link", link.kind = LiaKind::Spring, link.stiffness = 100;
        link.from = "other_bridge", link.to = "other_string";
        model.mats.push_back(other_bridge), model.mats.push_back(other_string);
        model.lias.push_back(link);
        EXPECT_EQ(string_points(model), shape);
    }
}

// The points nothing reads cost the step nothing: they are left out of it, and the string
// plays the same bytes as with its read points alone.
TEST(ModalString, TheStepLeavesOutThePointsNothingReads) {
    const Model model = build(Tuning::Homogeneous, Structure::Modal, 220, true);
    const CompiledModel compiled = compile(model);
    const CompiledLevel& audio = compiled.levels[0];
    EXPECT_EQ(audio.modal_points.size(), 3u) << "s1 and s60 (their links) and s7 (the bow)";
    EXPECT_EQ(audio.derived_points.size(), 57u);
    for (const CompiledModalPoint& p : audio.derived_points)
        EXPECT_GT(p.index, audio.size - audio.fixed_after) << "held after the chain loop's MATs";

    Model read_alone = model;
    std::erase_if(read_alone.mats, [](const Mat& m) {
        return m.kind == MatKind::ModalPoint && m.id != "s1" && m.id != "s7" && m.id != "s60";
    });
    Simulation with_all(compiled), with_read(compile(read_alone));
    std::vector<double> a(48000), b(48000);
    ASSERT_EQ(with_all.run(a), a.size());
    ASSERT_EQ(with_read.run(b), b.size());
    EXPECT_GT(*std::max_element(a.begin(), a.end()), 0.01) << "it was bowed";
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
}

// A bow with a width touches a string in modal form through a contact point of its own, so
// the point at the bowed mass keeps its shape. It plays the bytes it played when the bowed point
// itself held the mixed weights (before the bow could move along a modal string).
TEST(ModalString, AWideBowTouchesThroughItsOwnContactAndPlaysAsBefore) {
    const Model model = build(Tuning::Homogeneous, Structure::Modal, 440);
    const Lia* bow = model.find_lia("friction");
    ASSERT_NE(bow, nullptr);
    ASSERT_EQ(bow->bowed_string(), "bow_contact");
    const std::string centre = bowed_centre(model, *bow);
    ASSERT_EQ(centre.front(), 's');
    const int i = std::stoi(centre.substr(1));
    const Mat& before = *model.find_mat("s" + std::to_string(i - 1));
    const Mat& at = *model.find_mat(centre);
    const Mat& after = *model.find_mat("s" + std::to_string(i + 1));
    const Mat& contact = *model.find_mat("bow_contact");
    ASSERT_EQ(contact.weights.size(), at.weights.size());
    for (std::size_t k = 0; k < contact.weights.size(); ++k)
        ASSERT_EQ(contact.weights[k],
                  0.25 * before.weights[k] + 0.5 * at.weights[k] + 0.25 * after.weights[k]);
    const std::vector<std::string> shape = string_points(model);
    EXPECT_EQ(std::count(shape.begin(), shape.end(), "bow_contact"), 0)
        << "the contact is not a point of the string's shape";

    // The string as it was built before: the bowed point mixed, no contact.
    Model mixed = model;
    mixed.find_mat(centre)->weights = contact.weights;
    mixed.find_lia("friction")->to = centre;
    for (Probe& p : mixed.probes)
        if (p.element == "bow_contact") p.element = centre;
    std::erase_if(mixed.mats, [](const Mat& m) { return m.id == "bow_contact"; });
    Simulation now(compile(model)), then(compile(mixed));
    std::vector<double> a(24000), b(24000);
    ASSERT_EQ(now.run(a), a.size());
    ASSERT_EQ(then.run(b), b.size());
    EXPECT_GT(*std::max_element(a.begin(), a.end()), 0.01) << "it was bowed";
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
}

// bow.position moves the bow along a string in modal form, with a width or hair-wide: the
// string then plays the bytes of the one built with its bow there, and says where it is bowed.
TEST(ModalString, MovingTheBowPlaysAsTheStringBuiltThere) {
    const Gesture steady = load_gesture_file(test::resource("gestures/steady-bow.json"));
    for (bool point_bow : {false, true}) {
        BowedStringOptions o;
        o.pitch = 440, o.structure = Structure::Modal, o.point_bow = point_bow;
        o.bow_position = 0.12, o.bow_position_fixed = true;
        o.with_gesture = false, o.output_gain = 1.0;  // played with steady-bow.json
        Model moved = build_bowed_string(o);
        o.bow_position = 0.2;
        const Model built = build_bowed_string(o);
        set_variant_parameter(moved, "bow.position", 0.2);
        const std::string what = point_bow ? "hair-wide bow" : "bow with a width";
        EXPECT_EQ(bow_position(moved), bow_position(built)) << what;
        EXPECT_NEAR(bow_position(moved), 0.2, 0.01) << what;
        EXPECT_EQ(string_points(moved), string_points(built)) << what;
        Simulation a_sim(compile(moved)), b_sim(compile(built));
        a_sim.set_gesture_track(&steady), b_sim.set_gesture_track(&steady);
        std::vector<double> a(24000), b(24000);
        ASSERT_EQ(a_sim.run(a), a.size()) << what;
        ASSERT_EQ(b_sim.run(b), b.size()) << what;
        EXPECT_GT(*std::max_element(b.begin(), b.end()), 0.01) << what << ": it was bowed";
        EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0) << what;
    }
}

// A contact that is not the builder's mix of three points (edited by hand), or points around
// the new place that read other modes than the contact: the move is refused with the element
// named, and the model is left as it was (the bow is not made hair-wide behind the user's back).
TEST(ModalString, ABowMoveItCannotMakeIsRefusedAndChangesNothing) {
    BowedStringOptions o;
    o.pitch = 440, o.structure = Structure::Modal, o.with_gesture = false, o.output_gain = 1;
    const Model built = build_bowed_string(o);
    auto refused = [&](Model model, const std::string& named) {
        const std::string before = format_model(model);
        try {
            set_variant_parameter(model, "bow.position", 0.25);
            ADD_FAILURE() << "moved with " << named;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("\"" + named + "\""), std::string::npos)
                << e.what();
        }
        EXPECT_EQ(format_model(model), before) << named;
    };
    Model edited = built;
    edited.find_mat("bow_contact")->weights[0] *= 1.01;
    refused(edited, "bow_contact");
    Model other_modes = built;
    const int n = static_cast<int>(bow_stations(built).size());
    Mat& point = *other_modes.find_mat("s" + std::to_string(std::lround(0.25 * (n + 1)) + 1));
    point.modes.pop_back(), point.weights.pop_back();
    refused(other_modes, point.id);
}

TEST(ModalString, ValidationNamesABadModalPoint) {
    const Model good = build(Tuning::Homogeneous, Structure::Modal, 220, true);
    auto refused = [&](auto change, const std::string& expected) {
        Model m = good;
        change(*m.find_mat("s7"));
        try {
            validate_model(m);
            ADD_FAILURE() << "accepted: " << expected;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        }
    };
    refused([](Mat& p) { p.weights.pop_back(); }, "mass \"s7\": has 60 modes but 59 weights");
    refused([](Mat& p) { p.modes[3] = "surface"; }, "mode \"surface\" is a fixed");
    refused([](Mat& p) { p.modes[3] = "nowhere"; }, "mode \"nowhere\" is not a mass of this model");
    refused([](Mat& p) { p.modes.clear(), p.weights.clear(); }, "at least one mode");
}

}  // namespace
}  // namespace archet
