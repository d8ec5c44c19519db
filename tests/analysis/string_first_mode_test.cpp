// The string's first partial without eigenvectors against analyse_modes(): the same bits of
// f1 and of its decay, which maps, attack maps, comparisons and bowing reports measure by.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/string_first_mode.hpp"
#include "archet/analysis/string_partials.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/linear_system.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

void expect_the_whole_analysis_first_partial(const Model& model, const std::string& what) {
    const ModalAnalysis modes = analyse_modes(model);
    const StringFirstMode expected = string_first_mode(modes);
    ASSERT_GT(expected.frequency, 0.0) << what;
    ASSERT_GT(expected.t60, 0.0) << what;
    const StringFirstMode first = string_first_mode(model);
    EXPECT_EQ(first.frequency, expected.frequency) << what;  // to the bit
    EXPECT_EQ(first.t60, expected.t60) << what;
}

TEST(StringFirstMode, IsTheWholeAnalysisFirstPartialOnEveryShippedString) {
    int models = 0;
    for (const auto& entry : std::filesystem::directory_iterator(test::resource("models"))) {
        if (entry.path().extension() != ".json") continue;
        expect_the_whole_analysis_first_partial(load_model_file(entry.path()),
                                                entry.path().filename().string());
        ++models;
    }
    EXPECT_EQ(models, 16);
}

TEST(StringFirstMode, IsTheWholeAnalysisFirstPartialOnBuiltStrings) {
    // A chain with a body (a sparse solve), a paper chaplet (tridiagonal), a modal string
    // (modal points reading every mode), a short bare chain, and a finger (the whole analysis).
    BowedStringOptions body;
    body.pitch = 196;
    BowedStringOptions paper;
    paper.paper = true, paper.masses = 60;
    BowedStringOptions modal;
    modal.structure = Structure::Modal, modal.pitch = 440;
    BowedStringOptions bare;
    bare.body = "none", bare.pitch = 659.3;
    BowedStringOptions fingered;
    fingered.finger = true, fingered.finger_position = 0.75;
    for (const auto& [options, what] :
         {std::pair{body, "196 Hz with a body"}, std::pair{paper, "paper chaplet"},
          std::pair{modal, "modal 440 Hz"}, std::pair{bare, "659.3 Hz, no body"},
          std::pair{fingered, "fingered at 3/4"}})
        expect_the_whole_analysis_first_partial(build_bowed_string(options), what);
    // Which shape solve each takes: the body's bridge point joins more than neighbours.
    EXPECT_FALSE(is_tridiagonal(sounding_part(build_bowed_string(body))));
    EXPECT_TRUE(is_tridiagonal(sounding_part(build_bowed_string(paper))));
}

TEST(StringFirstMode, ThrowsWhatTheWholeAnalysisThrows) {
    Model empty;
    empty.name = "empty";
    EXPECT_THROW(string_first_mode(empty), InputError);
}

}  // namespace
}  // namespace archet
