// The studio's modal analysis, its eigenvalue solve made again only when the sounding part
// changes: the same result as analyse_modes() after every edit, to the bit.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/modal_analysis_cache.hpp"
#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/model_variants.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

void expect_same_analysis(const ModalAnalysis& a, const ModalAnalysis& b) {
    EXPECT_EQ(a.rate, b.rate);
    EXPECT_TRUE(same_bits(a.sample_rate, b.sample_rate));
    EXPECT_EQ(a.dofs, b.dofs);
    EXPECT_EQ(a.points, b.points);
    EXPECT_TRUE(same_bits(a.fundamental, b.fundamental));
    ASSERT_EQ(a.modes.size(), b.modes.size());
    for (std::size_t m = 0; m < a.modes.size(); ++m) {
        const ModeInfo &x = a.modes[m], &y = b.modes[m];
        EXPECT_TRUE(same_bits(x.frequency, y.frequency) && same_bits(x.t60, y.t60) &&
                    x.support == y.support && x.partial == y.partial &&
                    same_bits(x.cents, y.cents) && x.shape.size() == y.shape.size() &&
                    std::memcmp(x.shape.data(), y.shape.data(), x.shape.size() * sizeof(double)) ==
                        0)
            << "mode " << m;
    }
}

Model shipped(const std::string& name) {
    return load_model_file(test::resource("models/" + name + ".json"));
}

TEST(ModalAnalysisCache, AnalysesAgainOnlyWhenAnEditChangesWhatItReads) {
    ModalAnalysisCache cache;
    Model model = shipped("bowed-string-220-paper");
    expect_same_analysis(cache.of(model), analyse_modes(model));
    EXPECT_EQ(cache.solves(), 1u);
    // The bow's friction and its place on the string: the same string, solved once.
    set_parameter(model, ParameterName::parse("friction.mu_s"), 0.7);
    expect_same_analysis(cache.of(model), analyse_modes(model));
    set_variant_parameter(model, "bow.position", 0.2);
    expect_same_analysis(cache.of(model), analyse_modes(model));
    EXPECT_EQ(cache.solves(), 1u);
    // The string's damping: another string, solved again.
    set_variant_parameter(model, "string.damping", 0.002);
    const ModalAnalysis damped = cache.of(model);
    expect_same_analysis(damped, analyse_modes(model));
    EXPECT_EQ(cache.solves(), 2u);
    EXPECT_GT(damped.modes.front().t60, 0.0);
}

// A string with a body and a bow spread over three masses, which a modal point reads: moving
// the bow changes what that point reads, and so the analysis, but not the string's solve.
TEST(ModalAnalysisCache, ABowMovedAlongTheStringIsClassedAgainWithoutASolve) {
    ModalAnalysisCache cache;
    Model model = shipped("bowed-string-220");
    const ModalAnalysis before = cache.of(model);
    expect_same_analysis(before, analyse_modes(model));
    set_variant_parameter(model, "bow.position", 0.2);
    const ModalAnalysis moved = cache.of(model);
    expect_same_analysis(moved, analyse_modes(model));
    EXPECT_NE(moved.points, before.points) << "the contact point reads other masses";
    EXPECT_EQ(cache.solves(), 1u);
}

// What a modal point reads is part of the analysis to the bit: a weight turned from +0 to −0
// is read anew, not given as it was.
TEST(ModalAnalysisCache, AWeightOfMinusZeroIsNotOneOfPlusZero) {
    ModalAnalysisCache cache;
    Model model = shipped("bowed-string-220");
    Mat* point = nullptr;
    for (Mat& m : model.mats)
        if (m.kind == MatKind::ModalPoint && m.weights.size() > 1) point = &m;
    ASSERT_NE(point, nullptr);
    point->weights.back() = 0.0;
    cache.of(model);
    point->weights.back() = -0.0;
    const ModalAnalysis minus = cache.of(model);
    expect_same_analysis(minus, analyse_modes(model));
    EXPECT_TRUE(std::signbit(minus.points.at(point->id).back().second));
}

// An undo back to a string analysed a few edits before finds its solve; one analysed longer
// ago than the cache keeps is solved again, with the same result.
TEST(ModalAnalysisCache, KeepsTheLastFewSolvesForAnUndo) {
    ModalAnalysisCache cache;
    const Model original = shipped("bowed-string-110-paper");
    std::vector<Model> strings;
    for (std::size_t k = 0; k <= ModalAnalysisCache::kKept; ++k) {
        Model edited = original;
        set_variant_parameter(edited, "string.damping", 0.0005 * static_cast<double>(k + 1));
        strings.push_back(edited);
    }
    for (std::size_t k = 0; k < ModalAnalysisCache::kKept; ++k) cache.of(strings[k]);
    EXPECT_EQ(cache.solves(), ModalAnalysisCache::kKept);
    expect_same_analysis(cache.of(strings[0]), analyse_modes(strings[0]));  // undo, undo, …
    EXPECT_EQ(cache.solves(), ModalAnalysisCache::kKept);
    // One more string: the least recently used (strings[1], not strings[0]) makes room.
    cache.of(strings[ModalAnalysisCache::kKept]);
    cache.of(strings[0]);
    EXPECT_EQ(cache.solves(), ModalAnalysisCache::kKept + 1);
    expect_same_analysis(cache.of(strings[1]), analyse_modes(strings[1]));
    EXPECT_EQ(cache.solves(), ModalAnalysisCache::kKept + 2);
}

TEST(ModalAnalysisCache, RefusesWhatAnalyseModesRefusesEveryTime) {
    ModalAnalysisCache cache;
    Model model = shipped("bowed-string-220-paper");
    model.find_mat("s5")->mass = 0;
    std::string expected;
    try {
        analyse_modes(model);
    } catch (const InputError& e) {
        expected = e.what();
    }
    ASSERT_FALSE(expected.empty());
    for (int time = 0; time < 2; ++time) {
        try {
            cache.of(model);
            ADD_FAILURE() << "analysed a singular mass matrix";
        } catch (const InputError& e) {
            EXPECT_EQ(e.what(), expected);
        }
    }
    EXPECT_EQ(cache.solves(), 0u);
}

}  // namespace
}  // namespace archet
