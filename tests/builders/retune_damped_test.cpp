// The last step of a string's tuning: the damped first mode put on the pitch, looked at through
// one root at a time, and the roots it hands on those of the string it leaves.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/string_first_mode.hpp"
#include "archet/analysis/update_root_near.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/builders/string_chain.hpp"
#include "archet/model/linear_system.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

// The tuned string with its losses, as `archet new` hands it to retune_damped().
Model string_with_losses(const BowedStringOptions& o, int n) {
    Model model = tuned_string(o, n);
    const StringDecays d = string_decays(o);
    const StringElements elements = string_elements(n);
    apply_string_losses(model, elements,
                        solve_string_losses(model, elements, {d.low_hz, d.low_t60, "--string-t60"},
                                            {d.high_hz, d.high_t60, "--string-t60-high"}));
    return model;
}

void expect_on_the_pitch_with_its_roots(double pitch, int n) {
    BowedStringOptions o;
    o.pitch = pitch;
    Model model = string_with_losses(o, n);
    const LinearSystem before = assemble_linear_system(model, "audio");
    ASSERT_TRUE(
        update_root_near(before, std::polar(1.0, 2.0 * std::numbers::pi * pitch * before.dt)))
        << pitch << " Hz: the scalings look at one root, not the dense solve";
    const UpdateRoots roots = retune_damped(model, o, n);
    EXPECT_TRUE(identical(roots.system, assemble_linear_system(model, "audio")))
        << pitch << " Hz: the roots are the string's as it leaves";
    // The string's own first mode (its lowest mode with most of its energy in the string), not
    // merely the root nearest the pitch.
    EXPECT_LT(std::abs(string_first_mode(roots, model).frequency / pitch - 1.0), 1e-10)
        << pitch << " Hz";
}

TEST(RetuneDamped, PutsAViolinGsFirstModeOnThePitchAndHandsOnItsRoots) {
    expect_on_the_pitch_with_its_roots(196, 100);
}

TEST(RetuneDamped, PutsACelloCsFirstModeOnThePitchAndHandsOnItsRoots) {
    if (test::kUnderSanitizer) GTEST_SKIP() << test::kLargeStringUnderSanitizer;
    expect_on_the_pitch_with_its_roots(65, 364);  // the count `archet new` gives it
}

}  // namespace
}  // namespace archet
