// `archet compare`: one gesture on variants of a model, as in the paper's Fig. 5. More string
// damping makes the string dissipate more per period; the files and figure are written; a bad
// variation is refused before anything is written. And the named parameters themselves.

#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <nlohmann/json.hpp>

#include "archet/analysis/comparison.hpp"
#include "archet/analysis/playability.hpp"
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
TEST(Compare, VariantsOnTwoThreadsAreTheVariantsOneByOne) {
    const Model model = load_model_file(test::resource("models/bowed-string-220-paper.json"));
    const std::vector<double> values{0.0005, 0.005, 0.002};
    const ComparedVariants compared =
        compare_variants(model, *model.gesture, "string.damping", values, 0.4, 2);
    ASSERT_TRUE(compared.complete());
    ASSERT_EQ(compared.runs.size(), values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        SCOPED_TRACE(values[i]);
        const ComparisonRun alone =
            compare_variant(model, *model.gesture, "string.damping", values[i], 0.4);
        const ComparisonRun& run = compared.runs[i];
        EXPECT_EQ(run.label, alone.label);
        ASSERT_EQ(run.audio.size(), alone.audio.size());
        EXPECT_EQ(std::memcmp(run.audio.data(), alone.audio.data(), 8 * run.audio.size()), 0);
        EXPECT_EQ(run.bow_force, alone.bow_force);
        EXPECT_EQ(run.fundamental, alone.fundamental);
        EXPECT_EQ(run.dissipated_per_period, alone.dissipated_per_period);
    }
}

// A variant that fails keeps those before it and says why; a cancelled comparison starts none.
TEST(Compare, AFailedVariantKeepsThoseBeforeIt) {
    const Model model = load_model_file(test::resource("models/bowed-string-220-paper.json"));
    const ComparedVariants compared =
        compare_variants(model, *model.gesture, "string.damping", {0.0005, 1e6, 0.002}, 0.2, 1);
    EXPECT_EQ(compared.runs.size(), 1u);
    ASSERT_TRUE(compared.error);
    EXPECT_FALSE(compared.cancelled);
    try {
        std::rethrow_exception(compared.error);
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("unstable"), std::string::npos) << e.what();
    }
    const std::atomic<bool> cancel{true};
    const ComparedVariants none =
        compare_variants(model, *model.gesture, "string.damping", {0.0005, 0.002}, 0.2, 2, &cancel);
    EXPECT_TRUE(none.runs.empty());
    EXPECT_TRUE(none.cancelled);
    EXPECT_FALSE(none.error);
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

}  // namespace
}  // namespace archet
