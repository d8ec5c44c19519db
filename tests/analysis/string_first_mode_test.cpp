// The string's first partial without eigenvectors against analyse_modes(): the same bits of
// f1 and of its decay, which maps, attack maps, comparisons and bowing reports measure by, and
// the same class for every mode below it from a shape found from its root alone.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <string>
#include <vector>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/mode_shape.hpp"
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
    const auto partial_1 = std::find_if(modes.modes.begin(), modes.modes.end(),
                                        [](const ModeInfo& m) { return m.partial == 1; });
    ASSERT_NE(partial_1, modes.modes.end()) << what;
    const StringFirstMode first = string_first_mode(model);
    EXPECT_EQ(first.frequency, modes.fundamental) << what;  // to the bit
    EXPECT_EQ(first.t60, partial_1->t60) << what;
    // From roots solved beforehand (as a new string's tuning leaves them): the same bits.
    const StringFirstMode from_roots = string_first_mode(update_roots(sounding_part(model)), model);
    EXPECT_EQ(from_roots.frequency, modes.fundamental) << what;
    EXPECT_EQ(from_roots.t60, partial_1->t60) << what;
}

Model shipped(const std::string& name) {
    return load_model_file(test::resource("models/" + name + ".json"));
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
    // A chain with a body, a paper chaplet, a modal string (modal points reading every mode), a
    // short bare chain, and a finger (which takes the whole analysis).
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
}

// The modes up to f1, each classed from the shape its root alone gives (the string's first
// mode's own path, without its fall-backs) as the whole analysis classes it from its
// eigenvector. Returns how many of them are the supports'.
int expect_the_classes_of_the_modes_up_to_f1(const Model& model, const std::string& what) {
    const LinearSystem sys = sounding_part(model);
    const Eigen::EigenSolver<Eigen::MatrixXd> solver(update_matrix(sys), false);
    std::vector<std::complex<double>> roots;
    for (const std::complex<double>& z : solver.eigenvalues())
        if (z.imag() > 0.0) roots.push_back(z);
    std::sort(roots.begin(), roots.end(),
              [](const auto& a, const auto& b) { return std::arg(a) < std::arg(b); });
    const ModalAnalysis modes = analyse_modes(sys, model);
    EXPECT_EQ(roots.size(), modes.modes.size()) << what;
    const std::vector<bool> is_support = support_dofs(sys, model);
    int supports = 0;
    for (std::size_t r = 0; r < std::min(roots.size(), modes.modes.size()); ++r) {
        const auto shape = mode_shape(sys, roots[r]);
        EXPECT_TRUE(shape.has_value()) << what << ", mode " << r;
        if (!shape) break;
        const EnergySplit energy = energy_split(sys, is_support, *shape);
        EXPECT_TRUE(energy.finite()) << what << ", mode " << r;
        EXPECT_EQ(energy.support(), modes.modes[r].support) << what << ", mode " << r;
        if (modes.modes[r].partial == 1) break;
        ++supports;
    }
    return supports;
}

TEST(StringFirstMode, ClassesEveryModeBelowF1AsTheWholeAnalysisDoes) {
    // With a body, links join more than neighbours: the sparse solve.
    const Model body = shipped("bowed-string-440");
    ASSERT_FALSE(is_tridiagonal(sounding_part(body)));
    EXPECT_GE(expect_the_classes_of_the_modes_up_to_f1(body, "440 Hz with its body"), 1)
        << "the bridges' modes lie below f1";
    // A chaplet and its bridges: the tridiagonal solve.
    const Model paper = shipped("bowed-string-220-paper");
    ASSERT_TRUE(is_tridiagonal(sounding_part(paper)));
    EXPECT_GE(expect_the_classes_of_the_modes_up_to_f1(paper, "220 Hz paper chaplet"), 1);
}

// A new string tries the bow at the next masses when its own finds no Helmholtz band: along a
// chain the sounding part stays the tuned string's, whose roots its tuning solved, to the bit,
// so the first mode is read from those roots rather than solved again (seconds on a long
// string).
TEST(StringFirstMode, ABowMovedAlongAChainLeavesTheSoundingPartAsItWas) {
    BowedStringOptions here;
    here.pitch = 196, here.with_gesture = false;
    BowedStringOptions further = here;
    further.bow_position = here.bow_position + 0.03;
    const LinearSystem a = sounding_part(build_bowed_string(here));
    const LinearSystem b = sounding_part(build_bowed_string(further));
    EXPECT_TRUE(identical(a, b));
    // A modal string is made from the tuned chain once the bow's place is known: its sounding
    // part is not the chain's, and its first mode is solved anew.
    here.structure = Structure::Modal;
    EXPECT_FALSE(identical(a, sounding_part(build_bowed_string(here))));
}

// identical() tells one bit apart, in each part of a system.
TEST(StringFirstMode, IdenticalSystemsDifferInNoBit) {
    BowedStringOptions options;
    options.pitch = 440, options.with_gesture = false;
    const LinearSystem system = sounding_part(build_bowed_string(options));
    ASSERT_GT(system.stiffness.nonZeros(), 0);
    EXPECT_TRUE(identical(system, system));
    LinearSystem other = system;
    other.stiffness.uncompress();  // the same matrix stored otherwise
    EXPECT_TRUE(identical(system, other));
    auto one_ulp_up = [](double& v) { v = std::nextafter(v, 2 * v + 1); };
    other = system;
    one_ulp_up(other.mass[3]);
    EXPECT_FALSE(identical(system, other)) << "a mass";
    other = system;
    one_ulp_up(other.stiffness.valuePtr()[5]);
    EXPECT_FALSE(identical(system, other)) << "a stiffness";
    other = system;
    one_ulp_up(other.damping.valuePtr()[other.damping.nonZeros() - 1]);
    EXPECT_FALSE(identical(system, other)) << "a damping";
    other = system;
    one_ulp_up(other.dt);
    EXPECT_FALSE(identical(system, other)) << "the period";
    other = system;
    other.dofs[0] += "'";
    EXPECT_FALSE(identical(system, other)) << "a DOF's name";
    other = system;
    other.fingers.push_back({{{1, 1.0}}, 100.0, 0.1});
    EXPECT_FALSE(identical(system, other)) << "a finger";
}

TEST(StringFirstMode, ThrowsWhatTheWholeAnalysisThrows) {
    Model empty;
    empty.name = "empty";
    std::string whole, first;
    try {
        analyse_modes(empty);
    } catch (const InputError& e) {
        whole = e.what();
    }
    try {
        string_first_mode(empty);
    } catch (const InputError& e) {
        first = e.what();
    }
    EXPECT_FALSE(whole.empty());
    EXPECT_EQ(first, whole);
}

}  // namespace
}  // namespace archet
