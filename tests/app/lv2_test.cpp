// archet.lv2 hosted by lilv as a host would: the plugin is found in the build tree's bundle and
// is an instrument; a MIDI note plays the fingered string periodic at the note's pitch, its
// bow released by the note-off; run() allocates nothing; a new bow position is built in the
// worker and the string plays on through it; a patch:Set loads another model (a bad path keeps
// the one that plays) and the state keeps its path.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>

#include "archet/analysis/bowing_analysis.hpp"
#include "archet/files/model_file.hpp"
#include "archet/realtime_allocations.hpp"
#include "lv2_host.hpp"
#include "lv2_instrument.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

using test::Lv2Host;

constexpr std::uint32_t kBlock = 256;

std::vector<float> play(Lv2Host& host, double seconds) {
    std::vector<float> out;
    const auto blocks = static_cast<int>(seconds * 48000 / kBlock);
    for (int b = 0; b < blocks; ++b) {
        const std::vector<float> block = host.run(kBlock);
        out.insert(out.end(), block.begin(), block.end());
    }
    return out;
}

double rms(const std::vector<float>& x, std::size_t from, std::size_t to) {
    double sum = 0;
    for (std::size_t i = from; i < to; ++i) sum += static_cast<double>(x[i]) * x[i];
    return std::sqrt(sum / static_cast<double>(to - from));
}

struct Periodicity {
    double hz = 0;        ///< the fundamental, by the autocorrelation's first peak
    double strength = 0;  ///< the normalised autocorrelation there (1: exactly periodic)
};

// The period of the last `length` samples of `x`, searched between 80 and 1000 Hz.
Periodicity periodicity(const std::vector<float>& x, std::size_t length) {
    const std::size_t start = x.size() - length;
    auto r = [&](std::size_t lag) {
        double s = 0, a = 0, b = 0;
        for (std::size_t i = start; i + lag < x.size(); ++i) {
            s += static_cast<double>(x[i]) * x[i + lag];
            a += static_cast<double>(x[i]) * x[i];
            b += static_cast<double>(x[i + lag]) * x[i + lag];
        }
        return s / std::sqrt(a * b);
    };
    std::size_t best = 0;
    double best_r = -1;
    for (std::size_t lag = 48; lag <= 600; ++lag)  // the first strong peak: the period
        if (const double v = r(lag); v > best_r + 1e-9 && (best == 0 || v > 0.9 * best_r))
            if (v > best_r) best = lag, best_r = v;
    // Between samples: a parabola through the peak and its neighbours.
    const double l = r(best - 1), c = r(best), h = r(best + 1);
    const double shift = 0.5 * (l - h) / (l - 2 * c + h);
    return {48000.0 / (static_cast<double>(best) + shift), c};
}

TEST(Lv2, TheBundleIsAnInstrumentWithItsPorts) {
    Lv2Host host(ARCHET_LV2_BUNDLE);
    ASSERT_NE(host.plugin(), nullptr)
        << "lilv finds urn:archet:bowed-string in " << ARCHET_LV2_BUNDLE;
    const LilvPluginClass* kind = lilv_plugin_get_class(host.plugin());
    EXPECT_STREQ(lilv_node_as_string(lilv_plugin_class_get_label(kind)), "Instrument Plugin");
    EXPECT_EQ(lilv_plugin_get_num_ports(host.plugin()), 6u);
    for (const char* symbol :
         {"control", "out", "bow_force", "bow_speed", "bow_position", "string_damping"}) {
        LilvNode* s = lilv_new_string(host.world(), symbol);
        EXPECT_NE(lilv_plugin_get_port_by_symbol(host.plugin(), s), nullptr) << symbol;
        lilv_node_free(s);
    }
    ASSERT_TRUE(host.ready());
}

// The instrument run() plays, in this process: a note is bowed in Helmholtz motion at its pitch,
// read on the bow's slip velocity (one slip per period, steady), as the engine's notes are.
TEST(Lv2Instrument, ANoteIsBowedInHelmholtzMotionAtItsPitch) {
    lv2::Instrument instrument(load_model_file(std::string(ARCHET_LV2_BUNDLE) + "/default.json"),
                               48000, 0);
    instrument.set_controls(0.15, 0.1, 1.0);
    instrument.receive({midi::MidiMessage::Kind::NoteOn, 1, 64, 100});  // E4
    std::size_t slip = 0;
    for (std::size_t p = 0; p < instrument.simulation().probe_count(); ++p)
        if (instrument.simulation().model().probes[p].kind == ProbeKind::SlipVelocity) slip = p;
    std::vector<double> slips;
    float out[32];
    for (int b = 0; b < 1.5 * 48000 / 32; ++b) {
        for (int i = 0; i < 32; ++i) {
            instrument.render(out + i, 1);
            slips.push_back(instrument.simulation().probe(slip));
        }
    }
    const double e4 = 220 * std::pow(2.0, 7.0 / 12);
    const BowingAnalysis a = analyse_bowing(slips, 48000, e4, slips.size() - 24000, slips.size());
    EXPECT_TRUE(a.helmholtz()) << a.slips_per_period << " slips a period, spread "
                               << a.period_spread;
    EXPECT_LT(std::abs(a.pitch_cents), 20) << a.pitch_cents << " cents against E4";
    std::printf("the LV2 instrument's E4: %.3f slips a period, %+.1f cents\n", a.slips_per_period,
                a.pitch_cents);
}

// An instrument times the builds of its loop unless it is given one: the plugin gives a bow
// moved along the string the build its model was timed to, so that the move waits for no trials.
TEST(Lv2Instrument, RunsInTheBuildItIsGiven) {
    const Model model = load_model_file(std::string(ARCHET_LV2_BUNDLE) + "/default.json");
    for (ChainBuild build : {ChainBuild::Avx512, ChainBuild::Avx2, ChainBuild::Plain}) {
        if (!chain_build_runs_here(build)) continue;
        EXPECT_EQ(lv2::Instrument(model, 48000, 0.12, build).chain_build(), build)
            << chain_build_name(build);
    }
    EXPECT_TRUE(chain_build_runs_here(lv2::Instrument(model, 48000, 0.12).chain_build()));
}

TEST(Lv2, ANoteIsPlayedAtItsPitchWithoutAllocatingAndLiftedAtItsEnd) {
    Lv2Host host(ARCHET_LV2_BUNDLE);
    ASSERT_TRUE(host.ready());
    play(host, 0.1);
    host.midi({0x90, 64, 100});  // E4 on the fingered A3 string
    const std::uint64_t before = realtime_allocations() + realtime_deallocations();
    std::vector<float> note;
    for (int b = 0; b < static_cast<int>(1.5 * 48000 / kBlock); ++b) {
        const std::vector<float> block = host.run(kBlock, true);
        note.insert(note.end(), block.begin(), block.end());
    }
    EXPECT_EQ(realtime_allocations() + realtime_deallocations(), before)
        << "run() allocated or freed";
    const Periodicity p = periodicity(note, 24000);
    const double cents = 1200 * std::log2(p.hz / (220 * std::pow(2.0, 7.0 / 12)));
    EXPECT_LT(std::abs(cents), 20) << p.hz << " Hz";
    std::printf("E4 from archet.lv2: %.2f Hz (%+.1f cents), periodicity %.3f, rms %.4f\n", p.hz,
                cents, p.strength, rms(note, note.size() - 24000, note.size()));
    EXPECT_GT(p.strength, 0.9) << "periodic, as Helmholtz motion sounds";
    EXPECT_GT(rms(note, note.size() - 24000, note.size()), 1e-3) << "it sounds";
    host.midi({0x80, 64, 0});
    const std::vector<float> after = play(host, 3.0);
    EXPECT_LT(rms(after, after.size() - 4800, after.size()),
              0.1 * rms(note, note.size() - 24000, note.size()))
        << "released, the string dies away";
}

// A new bow position is compiled in the worker and swapped in: the string plays on through it
// (its motion carried over, not started again), and the sound changes with where it is bowed.
class Lv2Bow : public ::testing::TestWithParam<bool> {};

TEST_P(Lv2Bow, TheBowMovesAlongTheStringWhileItPlays) {
    Lv2Host host(ARCHET_LV2_BUNDLE);
    ASSERT_TRUE(host.ready());
    host.midi({0x90, 57, 100});  // the open A3
    const std::vector<float> before = play(host, 1.0);
    if (GetParam())
        host.control(2) = 0.2f;  // its port: β = 0.2, from the model's 0.12
    else
        host.midi({0xB0, 4, 64});  // STK's CC 4: β = 0.05 + 0.25 · 64/127 ≈ 0.176
    std::vector<float> after = play(host, 0.1);
    const std::vector<float> later = play(host, 1.0);
    after.insert(after.end(), later.begin(), later.end());
    const double playing = rms(before, before.size() - 4800, before.size());
    for (std::size_t at = 0; at + 480 <= 4800; at += 480)
        EXPECT_GT(rms(after, at, at + 480), 0.3 * playing)
            << "no gap at " << at << " samples after the move: the string played on";
    const Periodicity p = periodicity(after, 24000);
    EXPECT_LT(std::abs(1200 * std::log2(p.hz / 220.0)), 20) << p.hz;
    EXPECT_GT(p.strength, 0.9);
    EXPECT_GT(std::abs(rms(after, after.size() - 24000, after.size()) - playing), 0.05 * playing)
        << "bowed elsewhere, it sounds otherwise";
    host.midi({0x80, 57, 0});  // the note held across the move is released: the bow lifts
    const std::vector<float> released = play(host, 3.0);
    EXPECT_LT(rms(released, released.size() - 4800, released.size()), 0.1 * playing)
        << "the moved instrument knew the note it was playing";
}

INSTANTIATE_TEST_SUITE_P(ByPortAndByMidi, Lv2Bow, ::testing::Values(true, false));

// The string's damping at its port's extremes: held to what the scheme keeps stable, the string
// plays on (finite, sounding), more damped the more the port asks.
TEST(Lv2, TheDampingPortKeepsTheStringPlayable) {
    double loudness[2] = {0, 0};
    for (int i = 0; i < 2; ++i) {
        Lv2Host host(ARCHET_LV2_BUNDLE);
        ASSERT_TRUE(host.ready());
        host.control(3) = i == 0 ? 0.1f : 10.0f;
        host.midi({0x90, 57, 100});
        const std::vector<float> note = play(host, 1.0);
        for (float v : note) ASSERT_TRUE(std::isfinite(v));
        host.midi({0x80, 57, 0});
        const std::vector<float> after = play(host, 0.3);
        loudness[i] = rms(after, after.size() - 4800, after.size());
        EXPECT_GT(rms(note, note.size() - 24000, note.size()), 1e-3) << "it sounds";
    }
    EXPECT_GT(loudness[0], loudness[1]) << "the string rings on longer, less damped";
}

TEST(Lv2, APatchSetLoadsAnotherModelAndTheStateKeepsItsPath) {
    const auto dir = test::temp_dir("lv2-model");
    const auto model = dir / "open-110.json";
    const auto made = test::run_archet(
        {"new", "bowed-string", "--pitch", "110", "--paper", "--finger", "-o", model.string()});
    ASSERT_EQ(made.status, 0) << made.err;
    Lv2Host host(ARCHET_LV2_BUNDLE);
    ASSERT_TRUE(host.ready());
    EXPECT_NE(host.saved_model().find("default.json"), std::string::npos) << host.saved_model();
    host.set_model((dir / "missing.json").string());
    play(host, 0.05);
    EXPECT_NE(host.saved_model().find("default.json"), std::string::npos)
        << "a path that does not load keeps the model that plays";
    host.set_model(model.string());
    play(host, 0.05);
    EXPECT_EQ(host.saved_model(), model.string());
    host.midi({0x90, 45, 100});  // A2: the new string's open note, out of the old one's reach
    const std::vector<float> note = play(host, 1.5);
    EXPECT_GT(rms(note, note.size() - 24000, note.size()), 1e-3) << "the new string sounds";
    const Periodicity p = periodicity(note, 24000);
    // The paper's coarse chaplet, bowed hard, plays some 20 cents flat (pitch flattening).
    EXPECT_LT(std::abs(1200 * std::log2(p.hz / 110.0)), 30) << p.hz;
}

// A host's state:mapPath with the state:freePath its paths must be freed with: its own
// allocator (new[] here), never the plugin's free().
struct PathHost {
    int mapped = 0, freed = 0;
    static char* copy(const std::string& text) {
        char* p = new char[text.size() + 1];
        std::memcpy(p, text.c_str(), text.size() + 1);
        return p;
    }
    LV2_State_Map_Path map{this,
                           [](LV2_State_Map_Path_Handle h, const char* path) {
                               ++static_cast<PathHost*>(h)->mapped;
                               return copy(std::string("abstract:") + path);
                           },
                           [](LV2_State_Map_Path_Handle h, const char* path) {
                               ++static_cast<PathHost*>(h)->mapped;
                               return copy(std::string(path).substr(9));  // drops "abstract:"
                           }};
    LV2_State_Free_Path free{this, [](LV2_State_Free_Path_Handle h, char* path) {
                                 ++static_cast<PathHost*>(h)->freed;
                                 delete[] path;
                             }};
    LV2_Feature map_feature{LV2_STATE__mapPath, &map}, free_feature{LV2_STATE__freePath, &free};
    const LV2_Feature* features[3]{&map_feature, &free_feature, nullptr};
};

TEST(Lv2, TheStateMapsItsPathWithTheHostAndFreesItTheHostsWay) {
    Lv2Host host(ARCHET_LV2_BUNDLE);
    ASSERT_TRUE(host.ready());
    const std::string path = host.saved_model();
    PathHost paths;
    const std::string stored = host.saved_model(paths.features);
    EXPECT_EQ(stored, "abstract:" + path);
    EXPECT_TRUE(host.restore_model(stored, paths.features));
    EXPECT_EQ(host.saved_model(), path) << "restored from the host's abstract path";
    EXPECT_EQ(paths.mapped, 2);
    EXPECT_EQ(paths.freed, 2) << "each mapped path freed through state:freePath";
}

}  // namespace
}  // namespace archet
