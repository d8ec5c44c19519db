// The finger: a string stopped at a fifth or an octave rings at the modes the modal analysis
// predicts and, bowed, plays their pitch in Helmholtz motion; a light touch at the middle plays
// the octave harmonic; the finger keeps the energy books exact, and sliding it adds no energy
// beyond the pitch it raises and plays a glissando, not a click.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "archet/analysis/bowing_analysis.hpp"
#include "archet/analysis/modal_analysis.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/common/scheme_revision.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/scheme_changes.hpp"
#include "archet/physics/simulation.hpp"
#include "energy_books.hpp"

namespace archet {
namespace {

double cents(double f, double reference) {
    return 1200.0 * std::log2(f / reference);
}

Model fingered_string(double position, bool with_gesture = true) {
    BowedStringOptions o;
    o.pitch = 220;
    o.finger = true;
    o.finger_position = position;
    o.with_gesture = with_gesture;
    return build_bowed_string(o);
}

// The mean frequency of a signal's upward zero crossings (linearly interpolated) after `skip`.
double crossing_frequency(const std::vector<double>& x, double fs, std::size_t skip) {
    double first = -1, last = -1;
    int periods = -1;
    for (std::size_t i = skip + 1; i < x.size(); ++i)
        if (x[i - 1] < 0 && x[i] >= 0) {
            const double t = (i - 1 + x[i - 1] / (x[i - 1] - x[i])) / fs;
            if (first < 0) first = t;
            last = t, ++periods;
        }
    return periods > 0 ? periods / (last - first) : 0.0;
}

TEST(Finger, AStoppedStringRingsAtTheModesItsAnalysisPredicts) {
    // Below ½ the string behind the finger is the longer part: its modes are not the played
    // string's partials, and the first partial is still the sounding part's. (At 0.4 it would
    // sit on the violin body's mode near 550 Hz and split with it, as a wolf note does.)
    for (double position : {2.0 / 3.0, 0.5, 0.45}) {
        Model model = fingered_string(position, false);
        const ModalAnalysis modes = analyse_modes(model);
        const ModeInfo* first = nullptr;
        for (const auto& m : modes.modes)
            if (m.partial == 1) first = &m;
        ASSERT_NE(first, nullptr);
        // Struck in the stopped string's first mode shape, it rings at that mode. (The
        // string's masses are oscillators to their rest points, for their σ0 losses: they are
        // started by their velocity, their positions being their rest.)
        for (std::size_t d = 0; d < modes.dofs.size(); ++d)
            if (Mat* m = model.find_mat(modes.dofs[d]); m && m->id[0] == 's')
                m->velocity = 0.1 * first->shape[d];
        Simulation sim(compile(model));
        const MatSlot watched = sim.model().mat_slots.at("s13");
        std::vector<double> x;
        for (int i = 0; i < 24000; ++i) sim.step(), x.push_back(sim.position(watched));
        const double rings = crossing_frequency(x, sim.sample_rate(), 2400);
        EXPECT_NEAR(cents(rings, first->frequency), 0.0, 0.5)
            << "stopped at " << position << ": rings at " << rings << " Hz, predicted "
            << first->frequency << " Hz";
        EXPECT_NEAR(cents(first->frequency, 220.0 / position), 0.0, 30.0)
            << "the sounding part's first mode, not the part behind the finger";
    }
}

struct Bowed {
    BowingAnalysis steady;
    double f1 = 0;
};

// Bows a model with its own stroke and judges its steady part (1.5 s to the lift at 2.55 s)
// against `reference` Hz.
Bowed bow(const Model& model, double reference) {
    Simulation sim(compile(model));
    std::vector<double> slip;
    for (int i = 0; i < 2.6 * sim.sample_rate(); ++i)
        sim.step(), slip.push_back(sim.model().bows[0].slip_velocity);
    const double fs = sim.sample_rate();
    return {analyse_bowing(slip, fs, reference, static_cast<std::size_t>(1.5 * fs),
                           static_cast<std::size_t>(2.55 * fs)),
            analyse_modes(model).fundamental};
}

TEST(Finger, BowedAtAFifthAndAnOctaveItPlaysTheStoppedStringsPitch) {
    const double open = analyse_modes(fingered_string(1.0, false)).fundamental;
    for (double position : {2.0 / 3.0, 0.5}) {
        const Model model = fingered_string(position);
        const double stopped = analyse_modes(model).fundamental;
        const Bowed b = bow(model, stopped);
        EXPECT_TRUE(b.steady.helmholtz())
            << position << ": " << b.steady.slips_per_period << " slips per period";
        EXPECT_NEAR(b.steady.pitch_cents, 0.0, 10.0)
            << "stopped at " << position << ", its modes predict " << stopped << " Hz";
        const double played = stopped * std::exp2(b.steady.pitch_cents / 1200.0);
        if (position == 0.5)
            EXPECT_NEAR(cents(played, 2.0 * open), 0.0, 15.0) << "the octave: " << played << " Hz";
        else
            EXPECT_NEAR(cents(played, 1.5 * open), 0.0, 15.0) << "the fifth: " << played << " Hz";
    }
}

TEST(Finger, ALightTouchAtTheMiddlePlaysTheOctaveHarmonic) {
    Model model = fingered_string(1.0);
    Lia& finger = *model.find_lia("finger");
    finger.finger_position = 0.5;
    finger.pressure = 0.03;
    // The open string's second mode: a touch at its node leaves it alone.
    Model open = model;
    open.find_lia("finger")->pressure = 0;
    double second = 0;
    for (const auto& m : analyse_modes(open).modes)
        if (m.partial == 2) second = m.frequency;
    const Bowed b = bow(model, second);
    EXPECT_TRUE(b.steady.helmholtz()) << b.steady.slips_per_period << " slips per period";
    EXPECT_NEAR(b.steady.pitch_cents, 0.0, 15.0) << "against the open string's second mode";
}

// Two points that share modes cannot both be under one finger (its solve takes their
// responses as independent): validation says so, naming the finger.
TEST(Finger, ValidationRefusesTwoModalPointsAlongOneFinger) {
    Model model = fingered_string(1.0, false);
    Lia& finger = *model.find_lia("finger");
    finger.along.insert(finger.along.begin() + 1, "bow_contact");
    try {
        validate_model(model);
        FAIL() << "two modal points along one finger";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("a finger may touch one"), std::string::npos)
            << e.what();
    }
}

// Stored change − (hand work − dissipation) at every step, with the finger pressed between two
// masses; one rate level, where the identity is exact.
TEST(Finger, KeepsTheEnergyBooksExactAndDissipates) {
    BowedStringOptions o;
    o.pitch = 220, o.finger = true, o.finger_position = 0.7, o.haptic_divider = 1;
    Simulation sim(compile(build_bowed_string(o)));
    const test::Books books = test::step_by_step_books(sim, 48000);
    ASSERT_GT(books.scale, 0);
    EXPECT_LT(books.worst, 1e-9 * books.scale);
    const Model& source = sim.model().source;
    EXPECT_GT(sim.dissipated_by_element()[first_finger(source) - source.lias.data()], 0.0)
        << "its damper works";
}

// A finger between a modal point (the bridge) and a plain mass that another point reads (the
// first mass under the bow's hair) moves that point with the mass before the bow reads it, in
// whichever order it lists the two: that order is a name, not physics, so both give the same
// bytes (before revision 5, listing the bridge first left the hair's point behind the finger's
// push when the bow read it). Pressed halfway between them on a 63-mass string (its contact at
// exactly ½ of each).
TEST(Finger, OnAMassAModalPointReadsThatPointFollowsIt) {
    BowedStringOptions o;
    o.pitch = 220, o.masses = 63, o.finger = true, o.finger_position = 1.0 / 128;
    Model bridge_first = build_bowed_string(o);
    Mat* hair = bridge_first.find_mat("bow_contact");
    ASSERT_NE(hair, nullptr);
    hair->modes = {"s1", "s2", "s3"};
    bridge_first.probes = {{"hair", ProbeKind::Position, "bow_contact"}};
    Model mass_first = bridge_first;
    std::vector<std::string>& along = mass_first.find_lia("finger")->along;
    ASSERT_EQ(along.size(), 65u);
    std::swap(along[0], along[1]);  // s1, bridge, s2, …
    Simulation a(compile(bridge_first)), b(compile(mass_first));
    ASSERT_GE(a.model().levels[0].modal_point_of[a.model().mat_slots.at("bridge").index], 0)
        << "the bridge is a modal point";
    int apart = 0;
    double loudest = 0;
    for (int i = 0; i < 24000; ++i) {
        a.step(), b.step();
        const double sa = a.output(), sb = b.output(), pa = a.probe(0), pb = b.probe(0);
        apart += std::memcmp(&sa, &sb, sizeof sa) != 0 || std::memcmp(&pa, &pb, sizeof pa) != 0;
        loudest = std::max(loudest, std::abs(pa));
    }
    EXPECT_GT(loudest, 0.0) << "the bow moves the hair";
    EXPECT_EQ(apart, 0) << "the hair's point read stale modes when the finger listed the bridge "
                           "first";
    // A fix of scheme revision 5: a take played before it may re-render otherwise.
    EXPECT_EQ(scheme_change_since(a.model(), 4), SchemeChange::Fix);
    EXPECT_EQ(scheme_change_since(a.model(), 5), SchemeChange::None);
    o.finger_position = 0.75;  // the shipped string's: its hair is far from the bridge
    o.masses = 0;
    EXPECT_EQ(scheme_change_since(compile(build_bowed_string(o)), 4), SchemeChange::None);
}

// A finger position envelope: `from` until `start`, then to `to` over `seconds` (0: a jump).
void slide_finger(Model& model, double from, double to, double start, double seconds) {
    Control c;
    c.id = "slide", c.target = {"finger", "position"};
    c.envelope = {{0.0, from}, {start, from}, {start + std::max(seconds, 1e-9), to}};
    c.minimum = 0, c.maximum = 1;
    model.controls.push_back(c);
}

// A finger sliding up a ringing string does work on it: a slowly shortened string keeps E/f
// (the adiabatic invariant), so its energy may grow with its pitch, never more. Against the
// same string with the finger still, the sliding one never holds more than the still one
// times the pitch ratio 1/position: the slide adds no energy of its own. (It ends with less:
// the finger's damper takes what the part of the string it leaves behind held.)
TEST(Finger, SlidingOnARingingStringAddsNoMoreEnergyThanThePitchItRaises) {
    Model still = fingered_string(1.0, false);
    for (auto& m : still.mats)  // struck: velocity a triangle peaking at a third
        if (m.id[0] == 's' && m.id != "surface") {
            const double at = std::stod(m.id.substr(1)) / 108.0;
            m.velocity = 0.1 * (at < 1.0 / 3 ? 3 * at : 1.5 * (1 - at));
        }
    Model sliding = still;
    slide_finger(sliding, 1.0, 0.6, 0.05, 0.3);
    Simulation a(compile(still)), b(compile(sliding));
    const ParameterSlot position = b.model().resolve_parameter({"finger", "position"});
    double worst = 0;
    for (int i = 0; i < 0.5 * a.sample_rate(); ++i) {
        a.step(), b.step();
        worst = std::max(worst, b.stored_energy() * b.read_slot(position) / a.stored_energy());
    }
    // The invariant holds over a period, not at every sample: 1 % of slack.
    EXPECT_LE(worst, 1.01);
    EXPECT_GT(worst, 0.9) << "the same string until the slide";
}

// The largest sample-to-sample change of the output between two times (s).
double largest_step(const Simulation& sim, const std::vector<double>& y, double from, double to) {
    double worst = 0;
    for (auto i = static_cast<std::size_t>(from * sim.sample_rate()) + 1;
         i < static_cast<std::size_t>(to * sim.sample_rate()); ++i)
        worst = std::max(worst, std::abs(y[i] - y[i - 1]));
    return worst;
}

TEST(Finger, SlidingWhileBowingPlaysAGlissandoNotAClick) {
    auto play = [](double seconds) {
        Model model = fingered_string(1.0);
        slide_finger(model, 1.0, 0.75, 1.2, seconds);  // a fourth up
        auto sim = std::make_unique<Simulation>(compile(model));
        std::vector<double> y;
        for (int i = 0; i < 2.0 * sim->sample_rate(); ++i) sim->step(), y.push_back(sim->output());
        return std::pair{std::move(sim), y};
    };
    const auto [glide, smooth] = play(0.3);
    const double before = largest_step(*glide, smooth, 0.7, 1.2);
    const double during = largest_step(*glide, smooth, 1.2, 1.6);
    EXPECT_LT(during, 2.0 * before) << "a 0.3 s slide";
    const auto [jump, abrupt] = play(0.0);
    EXPECT_GT(largest_step(*jump, abrupt, 1.2, 1.6), 2.0 * before)
        << "the same move at once is the click the measure must see";
}

}  // namespace
}  // namespace archet
