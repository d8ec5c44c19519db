// `archet compare`: one gesture on variants of a model, as in the paper's Fig. 5. More string
// damping makes the string dissipate more per period; the files and figure are written; a bad
// variation is refused before anything is written. And the named parameters themselves.

#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "archet/analysis/comparison.hpp"
#include "archet/analysis/playability.hpp"
#include "archet/analysis/shared_first_modes.hpp"
#include "archet/analysis/string_first_mode.hpp"
#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_variants.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

TEST(Compare, MoreStringDampingDissipatesMorePerPeriod) {
    const auto dir = test::temp_dir("compare");
    const auto r =
        test::run_archet({"compare", test::resource("models/bowed-string-220-paper.json").string(),
                          "--vary", "string.damping=0.0005,0.005", "-o", (dir / "out").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto summary = nlohmann::json::parse(test::read_file(dir / "out" / "comparison.json"));
    ASSERT_EQ(summary["runs"].size(), 2u);
    const double low = summary["runs"][0]["dissipated_per_period_j"];
    const double high = summary["runs"][1]["dissipated_per_period_j"];
    EXPECT_GT(low, 0);
    EXPECT_GT(high, 2 * low) << "ten times the damping takes much more energy per period";
    EXPECT_NEAR(summary["runs"][0]["fundamental_hz"].get<double>(), 220, 0.1);
    for (const char* file : {"string.damping=0.0005.wav", "string.damping=0.005.wav",
                             "string.damping=0.0005.csv", "comparison.png"})
        EXPECT_GT(test::read_file(dir / "out" / file).size(), 10000u) << file;
    EXPECT_NE(r.out.find("dissipated per period"), std::string::npos) << r.out;
}

TEST(Compare, ABadVariationIsRefusedBeforeAnythingIsWritten) {
    const auto dir = test::temp_dir("compare-bad");
    const std::string model = test::resource("models/bowed-string-220.json").string();
    for (const auto& [vary, expected] : std::vector<std::pair<std::string, std::string>>{
             {"string.damping=0.001", "at least two values"},
             {"string.damping=0.001,x", "\"x\" is not a number"},
             {"bow.position=0.1,0.7", "β must be in (0, 0.5)"},
             {"nosuch.mass=1,2", "nosuch"},
             {"damping", "expected PARAM=V1,V2"}}) {
        const auto r =
            test::run_archet({"compare", model, "--vary", vary, "-o", (dir / "out").string()});
        EXPECT_EQ(r.status, 2) << vary;
        EXPECT_NE(r.err.find(expected), std::string::npos) << vary << ": " << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "out")) << vary;
    }
}

// The variants render on several threads, a variant each: the same runs as one at a time.
TEST(CompareVariants, OnTwoThreadsTheyAreTheVariantsOneByOne) {
    const Model model = load_model_file(test::resource("models/bowed-string-220-paper.json"));
    const std::vector<double> values{0.0005, 0.005, 0.002};
    const ComparedVariants compared =
        compare_variants(model, *model.gesture, "string.damping", values, 0.4, 2);
    ASSERT_TRUE(compared.complete());
    ASSERT_EQ(compared.runs.size(), values.size());
    auto same_bytes = [](const std::vector<double>& a, const std::vector<double>& b) {
        return a.size() == b.size() &&
               std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
    };
    for (std::size_t i = 0; i < values.size(); ++i) {
        SCOPED_TRACE(values[i]);
        const ComparisonRun alone =
            compare_variant(model, *model.gesture, "string.damping", values[i], 0.4);
        const ComparisonRun& run = compared.runs[i];
        EXPECT_EQ(run.label, alone.label);
        EXPECT_TRUE(same_bytes(run.audio, alone.audio));
        EXPECT_TRUE(same_bytes(run.bow_force, alone.bow_force));
        EXPECT_TRUE(same_bytes(run.displacement, alone.displacement));
        EXPECT_EQ(run.fundamental, alone.fundamental);
        EXPECT_EQ(run.dissipated_per_period, alone.dissipated_per_period);
    }
}

// A bow moved along the string leaves the string as it was, to the bit: its first mode is
// solved once for all the bow's variants, and is string_first_mode()'s to the bit; a variant of
// the string's damping is another string, solved again.
TEST(CompareVariants, ABowsVariantsShareTheirStringsSolve) {
    const Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    SharedFirstModes first_modes;
    auto expect_string_first_mode = [&](const std::string& parameter, double value) {
        SCOPED_TRACE(parameter + "=" + std::to_string(value));
        Model variant = model;
        set_variant_parameter(variant, parameter, value);
        const StringFirstMode shared = first_modes.of(variant);
        const StringFirstMode alone = string_first_mode(variant);
        EXPECT_GT(shared.frequency, 200.0);
        EXPECT_EQ(shared.frequency, alone.frequency);
        EXPECT_EQ(shared.t60, alone.t60);
    };
    for (double position : {0.08, 0.1, 0.13, 0.2})
        expect_string_first_mode("bow.position", position);
    EXPECT_EQ(first_modes.solves(), 1u);
    for (double damping : {0.0005, 0.002}) expect_string_first_mode("string.damping", damping);
    EXPECT_EQ(first_modes.solves(), 3u);
    expect_string_first_mode("string.damping", 0.002);
    EXPECT_EQ(first_modes.solves(), 3u);
}

// Threads asking for one string at once: one solves it, the others wait for its roots.
TEST(CompareVariants, ThreadsAskingForOneStringAtOnceSolveItOnce) {
    const Model model = load_model_file(test::resource("models/bowed-string-220-paper.json"));
    const StringFirstMode alone = string_first_mode(model);
    SharedFirstModes first_modes;
    std::vector<StringFirstMode> found(4);
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < found.size(); ++i)
        threads.emplace_back([&, i] {
            Model variant = model;
            set_variant_parameter(variant, "bow.position", 0.1 + 0.02 * static_cast<double>(i));
            found[i] = first_modes.of(variant);
        });
    for (std::thread& t : threads) t.join();
    EXPECT_EQ(first_modes.solves(), 1u);
    for (const StringFirstMode& first : found) {
        EXPECT_EQ(first.frequency, alone.frequency);
        EXPECT_EQ(first.t60, alone.t60);
    }
}

// And what it cannot analyse it says to each that asks, as string_first_mode() does.
TEST(CompareVariants, AStringThatCannotBeAnalysedIsRefusedToEachThatAsks) {
    Model model = load_model_file(test::resource("models/bowed-string-220-paper.json"));
    model.find_mat("s5")->mass = std::numeric_limits<double>::quiet_NaN();
    std::string expected;
    try {
        string_first_mode(model);
    } catch (const InputError& e) {
        expected = e.what();
    }
    ASSERT_FALSE(expected.empty());
    SharedFirstModes first_modes;
    for (int time = 0; time < 2; ++time) {
        try {
            first_modes.of(model);
            ADD_FAILURE() << "analysed a mass that is not a number";
        } catch (const InputError& e) {
            EXPECT_EQ(e.what(), expected);
        }
    }
}

std::string what_it_said(const std::exception_ptr& error) {
    try {
        std::rethrow_exception(error);
    } catch (const std::exception& e) {
        return e.what();
    }
}

// A variant that fails keeps the finished ones before it and says why, on one thread or two,
// wherever it comes.
TEST(CompareVariants, AFailedVariantKeepsThoseBeforeIt) {
    const Model model = load_model_file(test::resource("models/bowed-string-220-paper.json"));
    for (int jobs : {1, 2}) {
        SCOPED_TRACE(jobs);
        const ComparedVariants second = compare_variants(model, *model.gesture, "string.damping",
                                                         {0.0005, 1e6, 0.002}, 0.2, jobs);
        EXPECT_LE(second.runs.size(), 1u) << "the variants after a failure are left out";
        ASSERT_TRUE(second.error);
        EXPECT_FALSE(second.cancelled);
        EXPECT_NE(what_it_said(second.error).find("unstable"), std::string::npos);
        const ComparedVariants first = compare_variants(model, *model.gesture, "string.damping",
                                                        {1e6, 0.0005, 0.002}, 0.2, jobs);
        EXPECT_TRUE(first.runs.empty());
        ASSERT_TRUE(first.error);
        EXPECT_NE(what_it_said(first.error).find("unstable"), std::string::npos);
    }
    const ComparedVariants one =
        compare_variants(model, *model.gesture, "string.damping", {0.0005, 1e6}, 0.2, 1);
    EXPECT_EQ(one.runs.size(), 1u) << "on one thread the variant before finished";
}

// A cancel stops the variants under way, not only those not started.
TEST(CompareVariants, ACancelStopsTheVariantsUnderWay) {
    const Model model = load_model_file(test::resource("models/bowed-string-220-paper.json"));
    std::atomic<bool> cancel{false};
    // Set at the third progress report (a fifth of a second in), when both variants are under
    // way; rendered whole, two 60 s variants take far longer than a look every 4,096 samples.
    // (Should the threads not have started by then, none starts: the test still holds.)
    int reports = 0;
    const ComparedVariants stopped =
        compare_variants(model, *model.gesture, "string.damping", {0.0005, 0.002}, 60.0, 2, &cancel,
                         [&](std::size_t, std::size_t) {
                             if (++reports == 3) cancel = true;
                         });
    EXPECT_TRUE(stopped.cancelled);
    EXPECT_FALSE(stopped.error);
    EXPECT_TRUE(stopped.runs.empty());
    const ComparedVariants none =
        compare_variants(model, *model.gesture, "string.damping", {0.0005, 0.002}, 0.2, 2, &cancel);
    EXPECT_TRUE(none.runs.empty());
    EXPECT_TRUE(none.cancelled);
}

// From the command line, a variant that fails leaves no file of the others, nor their folder.
TEST(Compare, AVariantThatFailsLeavesNoFileOfTheOthers) {
    const auto dir = test::temp_dir("compare-unstable");
    const auto r = test::run_archet(
        {"compare", test::resource("models/bowed-string-220-paper.json").string(), "--vary",
         "string.damping=0.0005,1e6", "--seconds", "0.2", "-o", (dir / "out").string()});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("unstable"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << "nor the folder made for them";
}

TEST(Compare, BowPositionMovesAHairWideBowsContactPoint) {
    Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    int n = 0;
    while (model.find_mat("s" + std::to_string(n + 1))) ++n;
    set_variant_parameter(model, "bow.position", 0.2);
    const Mat* contact = model.find_mat(model.find_lia("friction")->bowed_string());
    const int centre = static_cast<int>(std::lround(0.2 * (n + 1)));
    EXPECT_EQ(contact->modes, (std::vector<std::string>{"s" + std::to_string(centre - 1),
                                                        "s" + std::to_string(centre),
                                                        "s" + std::to_string(centre + 1)}));
    EXPECT_NEAR(bow_position(model), 0.2, 0.5 / (n + 1));
}

TEST(Compare, BowPositionMovesTheBowAndItsProbes) {
    Model model = load_model_file(test::resource("models/bowed-string-220-paper.json"));
    set_variant_parameter(model, "bow.position", 0.2);
    const Lia* bow = model.find_lia("friction");
    EXPECT_EQ(bow->to, "s12") << "round(0.2 · 61)";
    for (const auto& p : model.probes)
        if (p.id == "bow_point_x" || p.id == "bow_point_v") {
            EXPECT_EQ(p.element, "s12");
        }
    set_variant_parameter(model, "string.damping", 0.003);
    const auto links = string_links(model);
    EXPECT_EQ(links.size(), 61u) << "bridge–s1, s1–s2, …, s60–nut";
    for (const auto& id : links) EXPECT_EQ(model.find_lia(id)->damping, 0.003);
    EXPECT_EQ(model.find_lia("bow_hold")->damping, 10.0) << "the hand's links are not the string";
}

// With two bow modules, β moves the one the pad, OSC and MIDI bow with and the studio shows:
// the first (first_bow()). It moved the last, while the engine moved the first.
TEST(Compare, BowPositionMovesTheFirstBowAsThePadPlaysIt) {
    Model model = load_model_file(test::resource("models/bowed-string-220-paper.json"));
    Lia second = *model.find_lia("friction");
    second.id = "second_bow", second.to = "s40";
    model.lias.push_back(second);
    set_variant_parameter(model, "bow.position", 0.2);
    EXPECT_EQ(first_bow(model)->id, "friction");
    EXPECT_EQ(model.find_lia("friction")->to, "s12") << "round(0.2 · 61)";
    EXPECT_EQ(model.find_lia("second_bow")->to, "s40") << "the other bow stays where it was";
}

}  // namespace
}  // namespace archet
