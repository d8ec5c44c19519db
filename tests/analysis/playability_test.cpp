// Playability maps: the regime classifier on constructed signals of each regime, and the map
// of the shipped 220 Hz string, which shows Schelleng's picture: a Helmholtz band between
// multiple slipping at low force and raucous motion at high force, whose lower edge falls as
// the bow moves away from the bridge. Shards merge into the same map. (At β 0.08, 0.14, 0.2
// and ten forces from 2 mN to 2 N it reads, from the least force up, s s s m m m m h r a /
// s s m m h h h h r r / s r m m h h h r r r: s silent, m multiple slip, h Helmholtz,
// r raucous, a anomalous low.)

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/playability.hpp"
#include "archet/common/denormal_guard.hpp"
#include "archet/files/model_file.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/simulation.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

constexpr double kFs = 48000, kPitch = 220;
constexpr std::size_t kSamples = 24000;

// Slip velocity with pulses of `width` (fraction of the period) at the given phases of each
// `periods`-long cycle; a sound that repeats with the same cycle.
struct Signals {
    std::vector<double> slip, sound;
};
Signals periodic(const std::vector<double>& phases, double width, double periods) {
    Signals s;
    const double cycle = periods * kFs / kPitch;
    for (std::size_t n = 0; n < kSamples; ++n) {
        const double u = std::fmod(static_cast<double>(n), cycle) / cycle;  // 0…1 in the cycle
        bool slipping = false;
        for (double p : phases) slipping = slipping || (u >= p && u < p + width / periods);
        s.slip.push_back(slipping ? -0.8 : 0.0);
        s.sound.push_back(u - 0.5 + 0.3 * std::sin(2 * std::numbers::pi * 3 * u));
    }
    return s;
}

TEST(Classifier, NamesEachRegimeOfConstructedSignals) {
    const Signals helmholtz = periodic({0.0}, 0.12, 1);
    EXPECT_EQ(classify_regime(helmholtz.slip, helmholtz.sound, kFs, kPitch).regime,
              Regime::Helmholtz);
    const Signals multiple = periodic({0.0, 0.45}, 0.06, 1);
    const auto m = classify_regime(multiple.slip, multiple.sound, kFs, kPitch);
    EXPECT_EQ(m.regime, Regime::MultipleSlip);
    EXPECT_NEAR(m.slips_per_period, 2.0, 0.05);
    const Signals low = periodic({0.0}, 0.12, 2);  // a period of two string periods
    const auto l = classify_regime(low.slip, low.sound, kFs, kPitch);
    EXPECT_EQ(l.regime, Regime::AnomalousLow);
    EXPECT_NEAR(l.pitch_cents, -1200, 10);
    std::mt19937 random(5);
    std::uniform_real_distribution<double> u(0, 1);
    Signals raucous;
    for (std::size_t n = 0; n < kSamples; ++n) {
        raucous.slip.push_back(u(random) < 0.1 ? 0.5 : 0.0);
        raucous.sound.push_back(u(random) - 0.5);
    }
    EXPECT_EQ(classify_regime(raucous.slip, raucous.sound, kFs, kPitch).regime, Regime::Raucous);
    const std::vector<double> still(kSamples, 0.0);
    EXPECT_EQ(classify_regime(still, still, kFs, kPitch).regime, Regime::Silent);
    // The spectral centroid of a 220 Hz sawtooth-like sound lies above its fundamental.
    EXPECT_GT(classify_regime(helmholtz.slip, helmholtz.sound, kFs, kPitch).centroid, kPitch);
}

TEST(PlayabilityMap, TheShippedStringShowsSchellengsPicture) {
    const Model model = load_model_file(test::resource("models/bowed-string-220-paper.json"));
    MapGrid grid;
    grid.force_min = 0.002, grid.force_max = 2.0, grid.force_steps = 10;
    grid.position_min = 0.08, grid.position_max = 0.2, grid.position_steps = 3;
    grid.duration = 1.0;
    const PlayedMap map = play_map(model, grid, 2);
    const std::vector<MapPoint>& points = map.points;
    ASSERT_EQ(points.size(), grid.size());
    std::string picture;
    std::vector<double> lowest_helmholtz;
    for (int j = 0; j < grid.position_steps; ++j) {
        // Along the force axis at this position: multiple slips, then Helmholtz, then raucous.
        std::vector<Regime> column;
        for (int i = 0; i < grid.force_steps; ++i)
            column.push_back(points[i * grid.position_steps + j].analysis.regime);
        for (Regime r : column) picture += std::string(to_string(r)).substr(0, 1);
        picture += " ";
        const auto first_h = std::find(column.begin(), column.end(), Regime::Helmholtz);
        ASSERT_NE(first_h, column.end())
            << "a Helmholtz band at β " << grid.position(j) << ": " << picture;
        // Below the band: multiple slipping (and, at the very least force, no sustained motion).
        EXPECT_NE(std::find(column.begin(), first_h, Regime::MultipleSlip), first_h)
            << "too little force slips several times a period: " << picture;
        EXPECT_TRUE(column.back() == Regime::Raucous || column.back() == Regime::AnomalousLow)
            << "too much force: " << picture;
        lowest_helmholtz.push_back(
            grid.force(static_cast<std::size_t>(first_h - column.begin()) * grid.position_steps));
    }
    EXPECT_GE(lowest_helmholtz.front(), lowest_helmholtz.back())
        << "the lower edge falls as the bow moves away from the bridge: " << picture;
    EXPECT_GT(lowest_helmholtz.front(), lowest_helmholtz.back() * 1.5) << picture;
    // Schelleng's own lines, from the string's parameters, bracket a band in the same place.
    const SchellengBounds b = schelleng_bounds(model, 0.12, grid.speed);
    EXPECT_GT(b.maximum, 10 * b.minimum);
    EXPECT_GT(b.maximum, 0.3);
    EXPECT_LT(b.maximum, 1.5) << "about 0.7 N for a violin-like string bowed at 0.1 m/s";
}

// A grid point played as maps played it before they ran the bowed chain's loop: tick by tick
// through step(), the slip read from the bow after each.
RegimeAnalysis stepped_point(const Model& model, const MapGrid& grid, std::size_t index,
                             double pitch, std::vector<double>& whole) {
    const MapStroke s = map_stroke(model, grid, index);
    Simulation sim(compile(s.variant));
    sim.set_gesture_track(&s.stroke);
    const DenormalGuard no_denormals;
    const auto total = static_cast<std::size_t>(grid.duration * sim.sample_rate());
    std::vector<double> slip, sound;
    for (std::size_t i = 0; i < total; ++i) {
        sim.step();
        whole.push_back(sim.output());
        if (i < total / 2) continue;
        slip.push_back(sim.model().bows[0].slip_velocity);
        sound.push_back(sim.output());
    }
    return classify_regime(slip, sound, sim.sample_rate(), pitch);
}

// A map plays each point in blocks through run(), the bowed chain's own loop, reading the bow's
// slip as a probe, in the build of the loop it found fastest: the bytes of the steps.
TEST(PlayabilityMap, APointPlaysTheStepsBytesInEveryBuild) {
    const Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    MapGrid grid;
    grid.force_min = grid.force_max = 0.3, grid.force_steps = 1;
    grid.position_min = grid.position_max = 0.12, grid.position_steps = 1;
    grid.duration = 0.5;
    std::vector<double> by_step;
    const RegimeAnalysis expected = stepped_point(model, grid, 0, kPitch, by_step);
    EXPECT_NE(expected.regime, Regime::Silent) << "the bow plays the string";
    for (ChainBuild build : {ChainBuild::Avx512, ChainBuild::Avx2, ChainBuild::Plain}) {
        if (!chain_build_runs_here(build)) continue;
        SCOPED_TRACE(chain_build_name(build));
        std::vector<double> by_run;
        const MapPoint got = play_map_point(model, grid, 0, kPitch, &by_run, build);
        ASSERT_EQ(by_run.size(), by_step.size());
        EXPECT_EQ(std::memcmp(by_run.data(), by_step.data(), by_run.size() * sizeof(double)), 0);
        EXPECT_EQ(got.analysis.regime, expected.regime);
        for (auto field : {&RegimeAnalysis::slips_per_period, &RegimeAnalysis::pitch_cents,
                           &RegimeAnalysis::slip_share, &RegimeAnalysis::centroid})
            EXPECT_EQ(std::memcmp(&(got.analysis.*field), &(expected.*field), 8), 0);
    }
}

// A map analyses the model's modes once, for its points' pitch and Schelleng's lines: what the
// points find is what each finds against its own variant's modes (the bow's place does not move
// them), and the lines are the model's.
TEST(PlayabilityMap, ReadsThePitchAndTheLinesFromOneAnalysisOfTheModel) {
    const Model model = load_model_file(test::resource("models/bowed-string-220-paper.json"));
    MapGrid grid;
    grid.force_min = 0.05, grid.force_max = 0.5, grid.force_steps = 2;
    grid.position_min = 0.07, grid.position_max = 0.18, grid.position_steps = 2;
    grid.duration = 0.3;
    const PlayedMap map = play_map(model, grid, 2);
    EXPECT_EQ(map.first_mode, analyse_modes(model).fundamental);
    const SchellengLines lines = schelleng_lines(model);
    EXPECT_GT(lines.impedance, 0);
    EXPECT_EQ(map.lines.impedance, lines.impedance);
    EXPECT_EQ(map.lines.resistance, lines.resistance);
    EXPECT_EQ(map.lines.friction_drop, lines.friction_drop);
    ASSERT_EQ(map.points.size(), grid.size());
    for (const MapPoint& point : map.points) {
        SCOPED_TRACE(point.index);
        const MapPoint alone = play_map_point(model, grid, point.index);  // its variant's modes
        EXPECT_EQ(point.analysis.regime, alone.analysis.regime);
        for (auto field : {&RegimeAnalysis::slips_per_period, &RegimeAnalysis::pitch_cents,
                           &RegimeAnalysis::slip_share, &RegimeAnalysis::centroid})
            EXPECT_EQ(std::memcmp(&(point.analysis.*field), &(alone.analysis.*field), 8), 0);
    }
}

TEST(PlayabilityMap, TheHelmholtzPointsPitchRangeIsTheirsAlone) {
    std::vector<MapPoint> points(4);
    const double cents[] = {-5.2, 900, -6.5, -5.8};
    const Regime regimes[] = {Regime::Helmholtz, Regime::MultipleSlip, Regime::Helmholtz,
                              Regime::Helmholtz};
    for (std::size_t i = 0; i < points.size(); ++i)
        points[i].analysis.regime = regimes[i], points[i].analysis.pitch_cents = cents[i];
    const HelmholtzPitch pitch = helmholtz_pitch(points);
    EXPECT_EQ(pitch.points, 3);
    EXPECT_EQ(pitch.flattest, -6.5);
    EXPECT_EQ(pitch.sharpest, -5.2) << "the multiple slip point's 900 cents is not a pitch";
    EXPECT_EQ(helmholtz_pitch({points[1]}).points, 0);
}

TEST(PlayabilityMap, ShardsMergeIntoTheWholeMap) {
    const Model model = load_model_file(test::resource("models/bowed-string-440.json"));
    const auto dir = test::temp_dir("map-shards");
    const std::string path = test::resource("models/bowed-string-440.json").string();
    const std::vector<std::string> grid{"--force",    "0.01:1:3", "--position", "0.1:0.15:2",
                                        "--duration", "0.4",      "--jobs",     "1"};
    auto run = [&](std::vector<std::string> extra) {
        std::vector<std::string> args{"map", path};
        args.insert(args.end(), grid.begin(), grid.end());
        args.insert(args.end(), extra.begin(), extra.end());
        return test::run_archet(args);
    };
    auto whole = run({"-o", (dir / "whole.csv").string()});
    ASSERT_EQ(whole.status, 0) << whole.err;
    // Two of its points are in Helmholtz motion: their pitch range is said.
    EXPECT_NE(whole.out.find("helmholtz: 2"), std::string::npos) << whole.out;
    EXPECT_NE(whole.out.find("cents against the first mode"), std::string::npos) << whole.out;
    for (int s = 0; s < 3; ++s) {
        const auto r = run({"--shard", std::to_string(s) + "/3", "-o",
                            (dir / ("part" + std::to_string(s) + ".csv")).string()});
        ASSERT_EQ(r.status, 0) << r.err;
    }
    const auto merged = test::run_archet(
        {"map", "merge", (dir / "part0.csv").string(), (dir / "part1.csv").string(),
         (dir / "part2.csv").string(), "--model", path, "-o", (dir / "merged.csv").string(),
         "--png", (dir / "map.png").string()});
    ASSERT_EQ(merged.status, 0) << merged.err;
    EXPECT_EQ(test::read_file(dir / "merged.csv"), test::read_file(dir / "whole.csv"))
        << "a sharded sweep is the same map, to the byte";
    EXPECT_GT(test::read_file(dir / "map.png").size(), 5000u);
    const auto missing = test::run_archet({"map", "merge", (dir / "part0.csv").string(), "--model",
                                           path, "-o", (dir / "bad.csv").string()});
    EXPECT_EQ(missing.status, 2);
    EXPECT_NE(missing.err.find("do not cover the grid"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace archet
