// Attack maps (Guettler diagrams): the transient judge on constructed slips, the wedge of
// perfect attacks on the shipped 220 Hz string, the CSV's round trip, and shards that merge into
// the whole map. (On that string, at 10 and 20 m/s² and forces from 0.4 to 3.8 N in 50 mN
// steps, it reads from the least force up, at 10 m/s²: m×23 P P m m m p×41; at 20 m/s²:
// m×51 P P P P P m m m m p×9. m: the transient began with a second slip in a period (most never
// settle), P: perfect, p: it began with a prolonged period.)
#include <gtest/gtest.h>

#include <algorithm>

#include "archet/analysis/attack.hpp"
#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

constexpr double kPeriod = 1.0 / 220;

// Slips: the given intervals (in periods) from a first slip at 3 ms, then steady periods; each
// slip lasts `slipping` of a period (Helmholtz motion bowed at β slips for β of it).
std::vector<Slip> slips_after(const std::vector<double>& transient, int steady,
                              double slipping = 0.12) {
    std::vector<double> t{0.003};
    for (double interval : transient) t.push_back(t.back() + interval * kPeriod);
    for (int i = 0; i < steady; ++i) t.push_back(t.back() + 1.004 * kPeriod);  // a little flat
    std::vector<Slip> slips;
    for (double onset : t) slips.push_back({onset, onset + slipping * kPeriod});
    return slips;
}

TEST(AttackJudge, HelmholtzFromTheFirstSlipIsPerfect) {
    const AttackTransient t = judge_transient(slips_after({}, 12), kPeriod, 1.0, 25);
    EXPECT_TRUE(t.decided);
    EXPECT_EQ(t.kind, AttackKind::Perfect);
    EXPECT_EQ(t.transient, Transient::None);
    EXPECT_EQ(t.periods, 0.0);
    EXPECT_EQ(t.slips, 0);
}

TEST(AttackJudge, ExtraSlipsAndLongPeriodsAreCountedInPeriods) {
    // Two slips a period for three periods, then Helmholtz motion.
    const AttackTransient multiple =
        judge_transient(slips_after({0.3, 0.7, 0.3, 0.7, 0.3, 0.7}, 12), kPeriod, 1.0, 25);
    EXPECT_EQ(multiple.kind, AttackKind::MultipleSlip);
    EXPECT_EQ(multiple.transient, Transient::MultipleSlip);
    EXPECT_NEAR(multiple.periods, 3.0, 1e-9);
    EXPECT_EQ(multiple.slips, 6);
    // Two prolonged periods (the string held too long), then Helmholtz motion.
    const AttackTransient prolonged =
        judge_transient(slips_after({1.6, 1.3}, 12), kPeriod, 1.0, 25);
    EXPECT_EQ(prolonged.kind, AttackKind::Prolonged);
    EXPECT_EQ(prolonged.transient, Transient::Prolonged);
    EXPECT_NEAR(prolonged.periods, 2.9, 1e-9);
    EXPECT_EQ(prolonged.slips, 2);
}

TEST(AttackJudge, NeverOnlyOnceNoLaterStartCouldCount) {
    std::vector<double> double_slips;  // two slips a period, for 50 periods
    for (int i = 0; i < 100; ++i) double_slips.push_back(i % 2 ? 0.7 : 0.3);
    const std::vector<Slip> slips = slips_after(double_slips, 0);
    const AttackTransient early = judge_transient(slips, kPeriod, 0.003 + 20 * kPeriod, 25);
    EXPECT_FALSE(early.decided) << "Helmholtz motion could still start within 25 periods";
    const AttackTransient late = judge_transient(slips, kPeriod, slips.back().onset, 25);
    EXPECT_TRUE(late.decided);
    EXPECT_EQ(late.kind, AttackKind::Never);
    EXPECT_EQ(late.transient, Transient::MultipleSlip);
    EXPECT_EQ(late.periods, 25.0);
    // Steady motion that starts after the periods allowed does not count.
    const AttackTransient too_late =
        judge_transient(slips_after(double_slips, 12), kPeriod, 1.0, 10);
    EXPECT_EQ(too_late.kind, AttackKind::Never);
    // One slip and no grip again: the bow slides. No slip at all: it is stuck.
    const AttackTransient sliding = judge_transient({{0.003}}, kPeriod, 1.0, 25);
    EXPECT_EQ(sliding.transient, Transient::Sliding);
    EXPECT_EQ(sliding.kind, AttackKind::Never);
    const AttackTransient stuck = judge_transient({}, kPeriod, 1.0, 25);
    EXPECT_EQ(stuck.transient, Transient::Stuck);
    EXPECT_EQ(stuck.kind, AttackKind::Never);
}

TEST(AttackJudge, SlipsThroughMostOfEachPeriodAreNotHelmholtzMotion) {
    // One slip a period, but each lasting 94 % of it: the bow slides and grips only briefly,
    // the motion at low force of the shipped strings. Helmholtz motion slips for β of it.
    const AttackTransient slid = judge_transient(slips_after({}, 40, 0.94), kPeriod, 1.0, 25);
    EXPECT_TRUE(slid.decided);
    EXPECT_EQ(slid.kind, AttackKind::Never);
    EXPECT_EQ(slid.transient, Transient::Sliding);
    // Two long slips, then Helmholtz motion: too little force at first, counted like extra slips.
    std::vector<Slip> settling = slips_after({1.0, 1.0}, 12);
    for (int i = 0; i < 2; ++i) settling[i].end = settling[i].onset + 0.8 * kPeriod;
    const AttackTransient settled = judge_transient(settling, kPeriod, 1.0, 25);
    EXPECT_EQ(settled.kind, AttackKind::MultipleSlip);
    EXPECT_EQ(settled.transient, Transient::Sliding);
    EXPECT_NEAR(settled.periods, 2.0, 1e-9);
    // Half of the period the slip begins, not of the string's: a prolonged period may hold a
    // longer slip and still be prolonged.
    std::vector<Slip> prolonged = slips_after({1.6}, 12);
    prolonged[0].end = prolonged[0].onset + 0.6 * kPeriod;
    EXPECT_EQ(judge_transient(prolonged, kPeriod, 1.0, 25).transient, Transient::Prolonged);
    prolonged[0].end = prolonged[0].onset + 0.9 * kPeriod;
    EXPECT_EQ(judge_transient(prolonged, kPeriod, 1.0, 25).transient, Transient::Sliding);
    // A second slip within the period names it, however long the first slip lasted.
    std::vector<Slip> doubled = slips_after({0.4, 0.6}, 12);
    doubled[0].end = doubled[0].onset + 0.3 * kPeriod;
    EXPECT_EQ(judge_transient(doubled, kPeriod, 1.0, 25).transient, Transient::MultipleSlip);
}

TEST(SlipDetection, EachSlipKeepsItsOwnEnd) {
    const double fs = 1000;
    std::vector<double> v(40, 0.0);
    for (int i : {0, 1, 2}) v[i] = 1;  // under way before the first sample: not a slip found
    for (int i = 10; i < 15; ++i) v[i] = -1;
    for (int i = 30; i < 40; ++i) v[i] = 1;  // still slipping at the last sample
    const std::vector<Slip> slips = slips_in(v, fs, 0, v.size());
    ASSERT_EQ(slips.size(), 2u);
    EXPECT_NEAR(slips[0].onset, 9.001 / fs, 1e-12) << "where |v| rises through 1 mm/s";
    EXPECT_EQ(slips[0].end, 15 / fs) << "the first sample under the threshold";
    EXPECT_NEAR(slips[1].onset, 29.001 / fs, 1e-12);
    EXPECT_FALSE(slips[1].ended());
    EXPECT_TRUE(slips[1].slid_through(1.0)) << "a slip not over yet has slid so far";
    EXPECT_FALSE(slips[0].slid_through(slips[0].onset + 0.02)) << "6 ms of a 20 ms period";
    EXPECT_TRUE(slips[0].slid_through(slips[0].onset + 0.01)) << "6 ms of a 10 ms period";
}

// The perfect attacks at one acceleration: [first, last] indices into the forces, or none.
struct PerfectBand {
    int first = -1, last = -1;
};
PerfectBand perfect_band(const std::vector<AttackPoint>& points, std::size_t from,
                         std::size_t count) {
    PerfectBand band;
    for (std::size_t i = 0; i < count; ++i) {
        if (points[from + i].transient.kind != AttackKind::Perfect) continue;
        if (band.first < 0) band.first = static_cast<int>(i);
        EXPECT_TRUE(band.last < 0 || band.last == static_cast<int>(i) - 1)
            << "the perfect attacks at one acceleration are one band of forces";
        band.last = static_cast<int>(i);
    }
    return band;
}

// The first index at or above `from` whose attack began with `transient`, or `count`.
std::size_t first_with(const std::vector<AttackPoint>& points, std::size_t offset, std::size_t from,
                       std::size_t count, Transient transient) {
    while (from < count && points[offset + from].transient.transient != transient) ++from;
    return from;
}

TEST(AttackMap, TheShippedStringHasAWedgeOfPerfectAttacks) {
    const Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    AttackGrid grid;
    grid.acceleration_min = 10, grid.acceleration_max = 20, grid.acceleration_steps = 2;
    grid.force_min = 0.4, grid.force_max = 3.8, grid.force_steps = 69;
    const AttackMap map = play_attack(model, grid, 2);
    EXPECT_NEAR(map.pitch, 220, 1e-6) << "periods of the string's own first mode";
    const std::vector<AttackPoint>& points = map.points;
    ASSERT_EQ(points.size(), grid.size());
    const std::size_t n = static_cast<std::size_t>(grid.force_steps);
    const PerfectBand slow = perfect_band(points, 0, n), fast = perfect_band(points, n, n);
    for (const auto& [band, from] : {std::pair{slow, std::size_t{0}}, std::pair{fast, n}}) {
        SCOPED_TRACE("acceleration " + std::to_string(points[from].acceleration) + " m/s²");
        ASSERT_GE(band.first, 1) << "too little force does not start Helmholtz motion at once";
        ASSERT_LE(band.last, static_cast<int>(n) - 2) << "nor does too much";
        ASSERT_GE(band.last - band.first, 1) << "a band, not a single lucky force";
        // Too little force: every attack below the band began with extra slips.
        for (int i = 0; i < band.first; ++i)
            EXPECT_EQ(points[from + static_cast<std::size_t>(i)].transient.transient,
                      Transient::MultipleSlip)
                << points[from + static_cast<std::size_t>(i)].force << " N";
        // Too much force: a little above the band, every attack began with a prolonged
        // period, up to the top of the sweep.
        const std::size_t prolonged =
            first_with(points, from, static_cast<std::size_t>(band.last), n, Transient::Prolonged);
        ASSERT_LT(prolonged, n) << "no prolonged periods above the band";
        EXPECT_LE(points[from + prolonged].force, points[from + band.last].force * 1.15)
            << "prolonged periods start just above the perfect attacks";
        for (std::size_t i = prolonged; i < n; ++i)
            EXPECT_EQ(points[from + i].transient.transient, Transient::Prolonged)
                << points[from + i].force << " N";
        EXPECT_GT(points[from + prolonged].first_slip, points[from].first_slip)
            << "more force holds the string longer before its first slip";
    }
    // Twice the acceleration needs more force at both edges: a wedge from the origin.
    EXPECT_GT(points[n + static_cast<std::size_t>(fast.first)].force,
              1.5 * points[static_cast<std::size_t>(slow.first)].force);
    EXPECT_GT(points[n + static_cast<std::size_t>(fast.last)].force,
              1.5 * points[static_cast<std::size_t>(slow.last)].force);
}

TEST(AttackMap, TheCsvReadsBackAsItWasWritten) {
    AttackGrid grid;
    grid.acceleration_steps = 2, grid.force_steps = 2, grid.log_axes = true, grid.position = 0.11;
    std::vector<AttackPoint> points(4);
    for (std::size_t i = 0; i < points.size(); ++i) {
        points[i].index = i;
        points[i].acceleration = grid.acceleration(i), points[i].force = grid.force(i);
        points[i].transient = {AttackKind::Prolonged, Transient::Prolonged, 2.5, 2, true};
        points[i].first_slip = 0.004;
    }
    points[3].transient = {AttackKind::Never, Transient::Sliding, 25, 1, true};
    points[2].first_slip = -1;
    const std::string text = format_attack({grid, points, 220});
    const AttackMap back = parse_attack(text, "map.csv");
    EXPECT_EQ(back.grid.describe(), grid.describe());
    EXPECT_EQ(back.pitch, 220);
    EXPECT_EQ(format_attack(back), text);
    EXPECT_EQ(back.points[3].transient.transient, Transient::Sliding);
    EXPECT_EQ(back.points[2].first_slip, -1);
    for (const auto& [bad, message] : std::vector<std::pair<std::string, std::string>>{
             {"index,a\n", "is not an archet attack map"},
             {"# archet-attack acceleration=1:2:2 force=0.1:0.2:2\n# f1 = 220 Hz\nindex\n0,1,0.1\n",
              "is short"},
             {"# archet-attack acceleration=1:2:2 force=0.1:0.2:2\n# f1 = 220 Hz\nindex\n"
              "0,1,0.1,superb,0,0,none,3\n",
              "is not an attack"},
             {"# archet-attack acceleration=1:2:2 force=0.1:0.2:2\n# f1 = 220 Hz\nindex\n"
              "9,1,0.1,perfect,0,0,none,3\n",
              "outside the grid"},
             {"# archet-attack acceleration=1:2:2 force=0.1:0.2:2 colour=red\n", "colour=red"},
             {"# archet-attack acceleration=1:2:0 force=0.1:0.2:2\n# f1 = 220 Hz\n",
              "STEPS ≥ 1 for the acceleration"},
             {"# archet-attack acceleration=1:2:2 force=0.1:0.2:2 periods-max=1e30\n",
              "periods-max from 1 to 1000"}}) {
        try {
            parse_attack(bad, "bad.csv");
            ADD_FAILURE() << "accepted: " << bad;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
    }
}

TEST(AttackMap, ShardsMergeIntoTheWholeMapAndBadGridsAreRefused) {
    const auto dir = test::temp_dir("attack-shards");
    const std::string path = test::resource("models/bowed-string-440.json").string();
    const std::vector<std::string> grid{"--acceleration", "4:16:2", "--force",
                                        "0.05:0.5:3",     "--jobs", "1"};
    auto run = [&](std::vector<std::string> extra) {
        std::vector<std::string> args{"attack", path};
        args.insert(args.end(), grid.begin(), grid.end());
        args.insert(args.end(), extra.begin(), extra.end());
        return test::run_archet(args);
    };
    const auto whole = run({"-o", (dir / "whole.csv").string()});
    ASSERT_EQ(whole.status, 0) << whole.err;
    for (int s = 0; s < 2; ++s) {
        const auto r = run({"--shard", std::to_string(s) + "/2", "-o",
                            (dir / ("part" + std::to_string(s) + ".csv")).string()});
        ASSERT_EQ(r.status, 0) << r.err;
    }
    const auto merged = test::run_archet(
        {"attack", "merge", (dir / "part0.csv").string(), (dir / "part1.csv").string(), "-o",
         (dir / "merged.csv").string(), "--png", (dir / "attack.png").string()});
    ASSERT_EQ(merged.status, 0) << merged.err;
    EXPECT_EQ(test::read_file(dir / "merged.csv"), test::read_file(dir / "whole.csv"))
        << "a sharded sweep is the same map, to the byte";
    EXPECT_GT(test::read_file(dir / "attack.png").size(), 5000u);
    const auto missing = test::run_archet(
        {"attack", "merge", (dir / "part0.csv").string(), "-o", (dir / "bad.csv").string()});
    EXPECT_EQ(missing.status, 2);
    EXPECT_NE(missing.err.find("do not cover the grid"), std::string::npos) << missing.err;
    for (const auto& [arguments, expected] :
         std::vector<std::pair<std::vector<std::string>, std::string>>{
             {{"--acceleration", "0:4:3"}, "expected 0 < MIN ≤ MAX ≤ 1000"},
             {{"--force", "0.5:0.1:3"}, "expected 0 < MIN ≤ MAX ≤ 100"},
             {{"--force", "lots"}, "expected MIN:MAX:STEPS"},
             {{"--axes", "polar"}, "expected linear or log"},
             {{"--shard", "2/2"}, "0 ≤ I < N"},
             {{"--periods-max", "0"}, "--periods-max"},
             {{"--jobs", "100000"}, "--jobs"},
             {{"--acceleration", "1:2:100000", "--force", "0.1:1:100000"},
              "more than --max-points"}}) {
        SCOPED_TRACE(arguments[0]);
        std::vector<std::string> args{"attack", path};
        args.insert(args.end(), arguments.begin(), arguments.end());
        args.insert(args.end(), {"-o", (dir / "refused.csv").string()});
        const auto r = test::run_archet(args);
        EXPECT_EQ(r.status, 2);
        EXPECT_NE((r.err + r.out).find(expected), std::string::npos) << r.err << r.out;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "refused.csv"));
}

}  // namespace
}  // namespace archet
