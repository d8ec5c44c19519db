// The full-bandwidth string: as many masses as the scheme allows at its pitch, two-parameter
// losses whose decays are the ones asked for (measured in simulation, after the bow leaves),
// and clear refusals beyond what the scheme or the losses allow (physics.md §2.3).

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/builders/string_chain.hpp"
#include "archet/builders/string_losses.hpp"
#include "archet/common/input_error.hpp"
#include "archet/model/gesture.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/simulation.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

int string_masses(const Model& m) {
    int n = 0;
    while (m.find_mat("s" + std::to_string(n + 1))) ++n;
    return n;
}

struct Size {
    double pitch;
    Tuning tuning;
};

class FullBandwidth : public ::testing::TestWithParam<Size> {};

TEST_P(FullBandwidth, HighestModeIsAtLeastFourFifthsOfWhatTheSchemeAllows) {
    if (test::kUnderSanitizer && GetParam().pitch == 110)
        GTEST_SKIP() << test::kLargeStringUnderSanitizer;
    BowedStringOptions o;
    o.pitch = GetParam().pitch, o.tuning = GetParam().tuning, o.with_gesture = false;
    const Model model = build_bowed_string(o);
    const int n = string_masses(model);
    const int most = o.tuning == Tuning::Harmonic ? max_harmonic_masses(o.pitch, o.sample_rate)
                                                  : max_stable_masses(o.pitch, o.sample_rate);
    EXPECT_GE(n, 0.8 * most) << n << " of at most " << most << " masses";
    // The scheme holds content up to fs/2; the string's highest mode reaches 80 % of it.
    const auto modes = string_mode_frequencies(model, string_elements(n));
    ASSERT_GE(static_cast<int>(modes.size()), n - 2) << "(a body's mode may take one or two)";
    EXPECT_GE(modes.back(), 0.8 * o.sample_rate / 2) << "highest mode " << modes.back() << " Hz";
}

INSTANTIATE_TEST_SUITE_P(
    PaperPitches, FullBandwidth,
    ::testing::Values(Size{110, Tuning::Homogeneous}, Size{220, Tuning::Homogeneous},
                      Size{440, Tuning::Homogeneous}, Size{880, Tuning::Homogeneous},
                      Size{110, Tuning::Harmonic}, Size{220, Tuning::Harmonic},
                      Size{440, Tuning::Harmonic}, Size{880, Tuning::Harmonic}));

// |Σ x·w·e^{−jωn}| over a Hann window: the amplitude of one partial.
double amplitude(const std::vector<double>& x, std::size_t from, std::size_t length, double f,
                 double fs) {
    std::complex<double> sum = 0;
    for (std::size_t i = 0; i < length; ++i) {
        const double w = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * i / (length - 1.0));
        sum += x[from + i] * w * std::polar(1.0, -2 * std::numbers::pi * f * i / fs);
    }
    return std::abs(sum);
}

// The 60 dB decay time of the partial near `f` in x[from…to), from a straight-line fit of its
// level in dB against time, the partial's frequency refined to the strongest near `f`.
double measured_t60(const std::vector<double>& x, std::size_t from, std::size_t to, double f,
                    double fs) {
    const auto window = static_cast<std::size_t>(0.08 * fs);
    double best = f, peak = 0;
    for (double g = f - 4; g <= f + 4; g += 0.05)
        if (const double a = amplitude(x, from, window, g, fs); a > peak) peak = a, best = g;
    double st = 0, sl = 0, stt = 0, stl = 0;
    int count = 0;
    for (std::size_t at = from; at + window <= to; at += window / 4) {
        const double t = at / fs, level = 20 * std::log10(amplitude(x, at, window, best, fs));
        st += t, sl += level, stt += t * t, stl += t * level, ++count;
    }
    const double slope = (count * stl - st * sl) / (count * stt - st * st);  // dB/s
    return -60.0 / slope;
}

struct Decay {
    double pitch, t60, t60_high;
    std::string body;
};

class FreeDecay : public ::testing::TestWithParam<Decay> {};

TEST_P(FreeDecay, TheDecaysAskedForAreTheOnesMeasuredAfterTheBowLeaves) {
    if (test::kUnderSanitizer && GetParam().pitch == 110)
        GTEST_SKIP() << test::kLargeStringUnderSanitizer;
    const Decay d = GetParam();
    BowedStringOptions o;
    o.pitch = d.pitch, o.string_t60 = d.t60, o.string_t60_high = d.t60_high, o.body = d.body;
    o.with_gesture = false;
    const Model model = build_bowed_string(o);
    // Bow for a second (any force sets every partial ringing), lift, and listen at the bow.
    const Gesture stroke = steady_bow_gesture(0.1, 0.0015, 1.4);
    Simulation sim(compile(model));
    sim.set_gesture_track(&stroke);
    std::size_t probe = 0;
    while (model.probes[probe].id != "bow_point_x") ++probe;
    const double fs = sim.sample_rate(), lifted = 1.1;
    const double listen = std::min(2.5, 1.2 * std::max(d.t60, d.t60_high));
    std::vector<double> x;
    for (std::size_t i = 0; i < static_cast<std::size_t>((lifted + listen) * fs); ++i) {
        sim.step();
        x.push_back(sim.probe(probe));
    }
    const auto from = static_cast<std::size_t>(lifted * fs);
    const StringDecays asked = string_decays(o);
    const int n = string_masses(model);
    for (auto [hz, t60] : {std::pair{asked.low_hz, d.t60}, std::pair{asked.high_hz, d.t60_high}}) {
        // The string's mode nearest the frequency asked for, where its partial is.
        Model bare = model;
        bare.lias.erase(bare.lias.end() - 3, bare.lias.end());  // bow_hold, press_hold, friction
        const double f = string_mode_decay(bare, string_elements(n), hz).frequency;
        const std::size_t to = from + static_cast<std::size_t>(std::min(listen, t60) * fs);
        EXPECT_NEAR(measured_t60(x, from, to, f, fs) / t60, 1.0, 0.15)
            << d.pitch << " Hz string, partial at " << f << " Hz";
    }
}

INSTANTIATE_TEST_SUITE_P(
    PaperPitches, FreeDecay,
    ::testing::Values(Decay{110, 3.0, 1.0, "none"}, Decay{220, 2.5, 0.8, "none"},
                      Decay{880, 1.5, 0.6, "none"}, Decay{110, 2.0, 0.25, "violin"},
                      Decay{220, 2.0, 0.2, "violin"}, Decay{880, 1.2, 0.2, "violin"}));

TEST(FullString, DefaultLossesAreTheViolinStringsOwnOnTopOfTheOthers) {
    // Desvages's loss model for the violin A string: about 10 s at 110 Hz, 2.2 s at 2 kHz.
    EXPECT_NEAR(violin_string_t60(110), 10.0, 0.5);
    EXPECT_NEAR(violin_string_t60(2000), 2.24, 0.05);
    EXPECT_GT(violin_string_t60(220), violin_string_t60(880));
    BowedStringOptions o;
    o.pitch = 220, o.body = "none", o.with_gesture = false;
    const Model model = build_bowed_string(o);
    // The string's own losses shorten the decay the bridges alone would give to about its own.
    const int n = string_masses(model);
    Model bare = model;
    bare.lias.erase(bare.lias.end() - 3, bare.lias.end());
    const double rate = string_mode_decay(bare, string_elements(n), 220).rate;
    EXPECT_GT(rate, std::log(1000.0) / violin_string_t60(220));
}

TEST(FullString, RefusesMoreMassesThanTheSchemeAllowsAndNamesTheLimit) {
    BowedStringOptions o;
    o.pitch = 440, o.masses = 80, o.with_gesture = false;
    try {
        build_bowed_string(o);
        FAIL() << "80 masses at 440 Hz are beyond the scheme";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "--masses");
        EXPECT_NE(std::string(e.what()).find(
                      "at most " + std::to_string(max_stable_masses(440, 48000)) + " masses"),
                  std::string::npos)
            << e.what();
    }
    o.masses = 40;  // any count below the limit is taken
    EXPECT_EQ(string_masses(build_bowed_string(o)), 40);
    o.paper = true, o.masses = 61;
    EXPECT_THROW(build_bowed_string(o), InputError) << "the paper's chaplets stop at 60";
}

TEST(FullString, RefusesDecaysTheLossesCannotGive) {
    BowedStringOptions o;
    o.pitch = 220, o.with_gesture = false, o.body = "none";
    o.string_t60 = 2.0, o.string_t60_high = 5.0;  // longer at 2 kHz than σ1 ≥ 0 allows
    try {
        build_bowed_string(o);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "--string-t60-high");
        EXPECT_NE(std::string(e.what()).find("must be at most"), std::string::npos) << e.what();
    }
    o.string_t60 = 2.0, o.string_t60_high = 0.0005;  // faster than link damping from 2 s
    EXPECT_THROW(build_bowed_string(o), InputError);
    o.string_t60 = 500.0, o.string_t60_high = 1.0;  // the bridges alone are faster
    try {
        build_bowed_string(o);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "--string-t60");
    }
}

// The default material (a violin A string's) at 30 Hz is a string 4.7 m long: no stroke plays
// it, and the refusal says which options make it a string an instrument has.
TEST(FullString, RefusesAStringNoInstrumentHasAndSaysWhichMaterialToGive) {
    BowedStringOptions o;
    o.pitch = 30, o.masses = 20, o.body = "none";
    try {
        build_bowed_string(o);
        FAIL() << "a 4.7 m violin A string was bowed";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("4.69 m long"), std::string::npos) << message;
        EXPECT_NE(message.find("--tension 57.1 N and --density 0.00072 kg/m, a violin A string's"),
                  std::string::npos)
            << message;
    }
    o.tension = 300, o.linear_density = 0.06;  // 1.18 m: near a five-string bass's low B
    const Model played = build_bowed_string(o);
    EXPECT_TRUE(played.gesture.has_value());
}

TEST(FullString, RefusesAMaterialWithoutTensionOrMassBeforeBuilding) {
    auto refused_on = [](double tension, double density) {
        BowedStringOptions o;
        o.tension = tension, o.linear_density = density;
        try {
            build_bowed_string(o);
        } catch (const InputError& e) {
            return e.where();
        }
        return std::string("nothing");
    };
    EXPECT_EQ(refused_on(0, 0.00072), "--tension");
    EXPECT_EQ(refused_on(2e4, 0.00072), "--tension");
    EXPECT_EQ(refused_on(57.1, -1), "--density");
    EXPECT_EQ(refused_on(57.1, std::nan("")), "--density");
    EXPECT_EQ(refused_on(57.1, 2), "--density");
}

TEST(FullString, TheBowRubsAHairWideContactPoint) {
    BowedStringOptions o;
    o.pitch = 220, o.with_gesture = false;
    const Model model = build_bowed_string(o);
    const Mat* contact = model.find_mat(model.find_lia("friction")->bowed_string());
    ASSERT_NE(contact, nullptr);
    ASSERT_EQ(contact->kind, MatKind::ModalPoint);
    ASSERT_EQ(contact->modes.size(), 3u);
    EXPECT_EQ(contact->weights, (std::vector<double>{0.25, 0.5, 0.25}));
    // The string's shortest wave (neighbours in opposition) does not move the contact point.
    double shortest = 0;
    for (std::size_t k = 0; k < 3; ++k) shortest += contact->weights[k] * (k % 2 ? -1.0 : 1.0);
    EXPECT_EQ(shortest, 0.0);
    o.point_bow = true;
    const Model point = build_bowed_string(o);
    EXPECT_NE(point.find_mat(point.find_lia("friction")->bowed_string())->kind,
              MatKind::ModalPoint);
}

}  // namespace
}  // namespace archet
