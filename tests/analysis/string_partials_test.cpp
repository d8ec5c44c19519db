// The string's partials without eigenvectors against analyse_modes() (the same bits, the
// harmonic tuning depends on them), and a chain mode's shape against the closed form.

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/string_partials.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/builders/string_chain.hpp"
#include "archet/builders/string_losses.hpp"
#include "archet/common/input_error.hpp"
#include "archet/model/linear_system.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

std::vector<double> partials_of_analyse_modes(const LinearSystem& sys, const Model& model) {
    std::vector<double> partials;
    for (const ModeInfo& mode : analyse_modes(sys, model).modes)
        if (!mode.support) partials.push_back(mode.frequency);
    return partials;
}

struct StringCase {
    double pitch;
    Tuning tuning;
    int masses;
    StringLosses losses;  // none: the string's tuning damps its bridges only
};

TEST(StringPartials, AreTheBitsAnalyseModesFindsOnTunedStrings) {
    const StringCase cases[] = {
        {220, Tuning::Harmonic, 96, {}},
        {220, Tuning::Harmonic, 96, {0.6, 1.6e-8}},
        {110, Tuning::Homogeneous, 120, {0.5, 2e-8}},
        {880, Tuning::Harmonic, 24, {1.2, 1e-8}},
        {1318.5, Tuning::Homogeneous, 12, {}},
    };
    for (const StringCase& c : cases) {
        BowedStringOptions o;
        o.pitch = c.pitch, o.tuning = c.tuning, o.body = "none";
        Model model = tuned_string(o, c.masses);
        apply_string_losses(model, string_elements(c.masses), c.losses);
        const LinearSystem sys = assemble_linear_system(model, "audio");
        ASSERT_TRUE(is_tridiagonal(sys)) << c.pitch << " Hz";
        const std::vector<double> expected = partials_of_analyse_modes(sys, model);
        ASSERT_EQ(expected.size(), static_cast<std::size_t>(c.masses)) << c.pitch << " Hz";
        EXPECT_EQ(string_partial_frequencies(sys, model), expected)
            << c.pitch << " Hz, " << c.masses << " masses, sigma0 " << c.losses.sigma0;
    }
}

TEST(StringPartials, AStringWithABodyIsNotAChainAndIsAnalysedWhole) {
    BowedStringOptions o;
    o.pitch = 440, o.body = "violin";
    const Model model = tuned_string(o, 40);
    const LinearSystem sys = assemble_linear_system(model, "audio");
    EXPECT_FALSE(is_tridiagonal(sys));  // the body's bridge point reads several modes
    EXPECT_EQ(string_partial_frequencies(sys, model), partials_of_analyse_modes(sys, model));
}

TEST(StringPartials, RefusesWhatAnalyseModesRefuses) {
    LinearSystem none;
    none.dt = 1.0 / 48000;
    EXPECT_THROW(string_partial_frequencies(none, Model{}), InputError);
    Model model = test::chain(4, 1e-4, 100.0, 0.0);
    model.find_mat("m2")->mass = 0.0;  // not validated here: the analysis names the mass
    const LinearSystem sys = assemble_linear_system(model);
    try {
        string_partial_frequencies(sys, model);
        FAIL() << "a massless DOF was analysed";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), "mass \"m2\"");
    }
}

// A uniform fixed–fixed chain with stiffness-proportional damping keeps the undamped shapes,
// sin(kπi/(N+1)), in every mode, whatever the damping does to its roots.
TEST(ChainModeShape, IsTheStandingWaveOfAUniformChain) {
    constexpr int kN = 30;
    constexpr double kFs = 48000, kMass = 1e-4, kK = 0.6 * kMass * kFs * kFs;
    const Model model = test::chain(kN, kMass, kK, 1e-7 * kK, kFs);
    const LinearSystem sys = assemble_linear_system(model);
    const auto modes = discrete_modes(sys);
    ASSERT_EQ(modes.size(), static_cast<std::size_t>(kN));
    for (int k = 1; k <= kN; ++k) {
        const DiscreteMode& mode = modes[k - 1];
        ASSERT_LT(mode.radius, 1.0);  // damped
        const std::complex<double> z =
            std::polar(mode.radius, 2.0 * std::numbers::pi * mode.frequency / kFs);
        const auto shape = chain_mode_shape(sys, z);
        std::complex<double> overlap = 0;
        double norm = 0;
        for (int i = 1; i <= kN; ++i) {
            const double standing = std::sin(k * std::numbers::pi * i / (kN + 1));
            overlap += standing * shape[i - 1];
            norm += standing * standing;
        }
        EXPECT_NEAR(std::abs(overlap) / std::sqrt(norm), 1.0, 1e-9) << "mode " << k;
    }
}

// The string mode nearest a frequency, from the eigenvalues and the nearest modes' shapes,
// against the whole eigenbasis: with a body, whose own modes lie among the string's and are
// passed over, and without.
TEST(StringModeFrequency, IsTheBitsTheWholeEigenbasisGives) {
    struct Case {
        double pitch;
        int masses;
        const char* body;
    };
    for (const Case& c : {Case{110, 100, "violin"}, Case{220, 96, "violin"}, Case{440, 40, "none"},
                          Case{65.4, 60, "violin"}}) {
        BowedStringOptions o;
        o.pitch = c.pitch, o.body = c.body;
        const Model model = tuned_string(o, c.masses);
        const StringElements string = string_elements(c.masses);
        for (double f : {c.pitch, 2.0 * c.pitch, 280.0, 470.0, 2000.0, 9000.0})
            EXPECT_EQ(string_mode_frequency(model, string, f),
                      string_mode_decay(model, string, f).frequency)
                << c.pitch << " Hz string, body " << c.body << ", near " << f << " Hz";
    }
}

}  // namespace
}  // namespace archet
