// The string's partials, each root found from its undamped mode, against the dense solve and
// analyse_modes() (the harmonic tuning depends on them), and a chain mode's shape against the
// closed form.

#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <set>
#include <string>

#include "archet/analysis/chain_update_roots.hpp"
#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/mode_shape.hpp"
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

// How far z is from a root: the smallest |P(z)·x| over unit shapes x (inverse iteration), in
// units of the largest mass.
double residual(const LinearSystem& system, std::complex<double> z) {
    const Eigen::SparseMatrix<std::complex<double>> p = quadratic_pencil(system, z);
    const Eigen::SparseLU<Eigen::SparseMatrix<std::complex<double>>> lu(p);
    Eigen::VectorXcd x = Eigen::VectorXcd::LinSpaced(system.size(), 1.0, 2.0);
    for (int pass = 0; pass < 4; ++pass) x = lu.solve(x).normalized();
    return (p * x).norm() / system.mass.maxCoeff();
}

// What rounding alone leaves of |P(z)·x| for a unit x, in the same units: a few roundings of
// P's largest column.
double rounding_residual(const LinearSystem& system, std::complex<double> z) {
    const Eigen::SparseMatrix<std::complex<double>> p = quadratic_pencil(system, z);
    double largest_column = 0;
    for (int column = 0; column < p.outerSize(); ++column) {
        double sum = 0;
        for (Eigen::SparseMatrix<std::complex<double>>::InnerIterator it(p, column); it; ++it)
            sum += std::abs(it.value());
        largest_column = std::max(largest_column, sum);
    }
    return 4.0 * std::numeric_limits<double>::epsilon() * largest_column / system.mass.maxCoeff();
}

// The dense solve's roots carry an error of a modest multiple of n·ε·‖U‖ (U the 2n × 2n
// update; 16 of them is the bound here): each root found from its undamped mode is the dense
// solve's nearest it to that, a distinct one, and as near a root (the residuals are at rounding
// for both: within twice the dense solve's and a few roundings of P), and the partials agree to
// that. (Refined in long double, the roots found from the modes were within 1e-16 of the
// refined ones on the 65 Hz string, the dense solve's within 1e-13 to 1e-15: the dense solve is
// the less exact.)
TEST(StringPartials, AreTheDenseSolvesOnTunedStrings) {
    const StringCase cases[] = {
        {220, Tuning::Harmonic, 96, {}},
        {220, Tuning::Harmonic, 96, {0.6, 1.6e-8}},
        {110, Tuning::Homogeneous, 120, {0.5, 2e-8}},
        {880, Tuning::Harmonic, 24, {1.2, 1e-8}},
        {1318.5, Tuning::Homogeneous, 12, {}},
        {65, Tuning::Harmonic, 300, {0.57, 1.6e-8}},  // a cello's C: the top partials crowd
    };
    for (const StringCase& c : cases) {
        const std::string what = std::to_string(c.pitch) + " Hz, " + std::to_string(c.masses) +
                                 " masses, sigma0 " + std::to_string(c.losses.sigma0);
        BowedStringOptions o;
        o.pitch = c.pitch, o.tuning = c.tuning, o.body = "none";
        Model model = tuned_string(o, c.masses);
        apply_string_losses(model, string_elements(c.masses), c.losses);
        const LinearSystem sys = assemble_linear_system(model, "audio");
        ASSERT_TRUE(is_tridiagonal(sys)) << what;
        const UpdateRoots dense = update_roots(sys);
        ASSERT_TRUE(dense.converged) << what;
        const auto roots = chain_update_roots(sys);
        ASSERT_TRUE(roots.has_value()) << what;
        ASSERT_EQ(roots->size(), static_cast<std::size_t>(sys.size())) << what;
        const Eigen::MatrixXd u = update_matrix(sys);
        const double bound = 16.0 * static_cast<double>(u.rows()) *
                             std::numeric_limits<double>::epsilon() *
                             u.cwiseAbs().rowwise().sum().maxCoeff();
        std::set<int> matched;
        for (const std::complex<double>& z : *roots) {
            int nearest = 0;
            for (int i = 0; i < static_cast<int>(dense.roots.size()); ++i)
                if (std::abs(dense.roots[i] - z) < std::abs(dense.roots[nearest] - z)) nearest = i;
            const std::complex<double> twin = dense.roots[nearest];
            EXPECT_TRUE(matched.insert(nearest).second) << what << ": two roots on one";
            EXPECT_LE(std::abs(z - twin), bound) << what;
            EXPECT_LE(residual(sys, z), 2.0 * residual(sys, twin) + rounding_residual(sys, z))
                << what;
        }
        const std::vector<double> expected = partials_of_analyse_modes(sys, model);
        const std::vector<double> partials = string_partial_frequencies(sys, model);
        ASSERT_EQ(expected.size(), static_cast<std::size_t>(c.masses)) << what;
        ASSERT_EQ(partials.size(), expected.size()) << what;
        // |Δf| = |Δ arg z|·fs/2π, and |Δ arg z| ≤ |Δz| / |z| with |z| near 1.
        const double frequency_bound = 2.0 * bound / (2.0 * std::numbers::pi * sys.dt);
        for (std::size_t k = 0; k < partials.size(); ++k)
            EXPECT_NEAR(partials[k], expected[k], frequency_bound) << what << ", partial " << k + 1;
    }
}

// A mode that does not oscillate (a ground damped past critical) has no pair of roots to find
// from its shape: the dense solve takes over, and the partials are analyse_modes()' own.
TEST(StringPartials, LeaveAnOverdampedChainToTheDenseSolve) {
    Model model = test::chain(6, 1e-4, 100.0, 0.0);
    Mat* grounded = model.find_mat("m3");
    grounded->kind = MatKind::Oscillator, grounded->stiffness = 1.0, grounded->damping = 10.0;
    const LinearSystem sys = assemble_linear_system(model);
    EXPECT_FALSE(chain_update_roots(sys).has_value());
    // The dense solve's roots are analyse_modes()' to the bit (the same reduction and steps).
    EXPECT_EQ(string_partial_frequencies(sys, model), partials_of_analyse_modes(sys, model));
}

// Two halves of a chain, eight masses, joined by a link far weaker than the others: their modes
// come in close pairs. Damped alike (the dampers in proportion to the springs), the undamped
// shapes are the damped modes' own, each root lies on its guess, and all are found. Damped on
// one half only, each damped mode keeps to one half while a pair's undamped shapes spread over
// both, so a pair's guesses fall between its roots:
// - with identical halves (the coupling a millionth of the other springs), half way: the
//   refinement from there cannot choose between the two roots and does not settle;
// - with the right half's masses a thousandth heavier (the coupling a hundredth), nearer one
//   root than the other but not nearer its own than half way to the other guess: the roots
//   may have settled each on its own, but nothing shows that two did not settle on one.
// Both are refused, and the dense solve takes over.
TEST(StringPartials, LeaveRootsTheirGuessesDoNotTellApartToTheDenseSolve) {
    auto halves = [](double coupling, double heavier, double left_damping, double right_damping) {
        Model model = test::chain(8, 1e-4, 100.0, 0.0);
        for (int i = 0; i <= 8; ++i)
            model.find_lia("l" + std::to_string(i))->damping = i < 4 ? left_damping : right_damping;
        for (int i = 5; i <= 8; ++i) model.find_mat("m" + std::to_string(i))->mass *= heavier;
        model.find_lia("l4")->stiffness = coupling;
        model.find_lia("l4")->damping = 0.0;
        return model;
    };
    const LinearSystem alike = assemble_linear_system(halves(1e-4, 1.0, 1e-3, 1e-3));
    ASSERT_TRUE(is_tridiagonal(alike));
    const auto found = chain_update_roots(alike);
    ASSERT_TRUE(found.has_value());
    EXPECT_EQ(found->size(), 8u);

    for (const Model& one_sided : {halves(1e-4, 1.0, 1e-3, 0.0), halves(1.0, 1.001, 1e-3, 0.0)}) {
        const LinearSystem system = assemble_linear_system(one_sided);
        EXPECT_FALSE(chain_update_roots(system).has_value());
        // The dense solve's roots are analyse_modes()' to the bit (the same reduction and steps).
        const std::vector<double> partials = string_partial_frequencies(system, one_sided);
        EXPECT_EQ(partials, partials_of_analyse_modes(system, one_sided));
        EXPECT_EQ(partials.size(), 8u);
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

// The modes that live in the string by their shares of inertia from the whole eigenbasis.
std::vector<double> string_modes_of_the_eigenbasis(const Model& model,
                                                   const StringElements& string) {
    const LinearSystem sys = assemble_linear_system(model, "audio");
    const int n = sys.size();
    const Eigen::VectorXd scale = sys.mass.cwiseSqrt().cwiseInverse();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(
        scale.asDiagonal() * Eigen::MatrixXd(sys.stiffness) * scale.asDiagonal());
    std::vector<double> frequencies;
    for (int mode = 0; mode < n; ++mode) {
        double share = 0;
        for (int d = 0; d < n; ++d)
            for (const std::string& id : string.masses)
                if (sys.dofs[d] == id) share += std::pow(solver.eigenvectors()(d, mode), 2);
        const double s = std::sqrt(std::max(0.0, solver.eigenvalues()[mode])) * sys.dt / 2;
        if (share >= 0.5)
            frequencies.push_back(std::asin(std::min(1.0, s)) / (std::numbers::pi * sys.dt));
    }
    return frequencies;
}

// A string between like bridges is mirror-symmetric: its odd modes are all but orthogonal to an
// even start, from which two solves of inverse iteration left a shape a twentieth off. Light
// bridges resonant among the string's partials (a third of its mass, at 158.5 Hz) put a bridge's
// mode at a share of 0.478, which that shape counted as the string's (0.530; bridges as heavy as
// the string resonant at 441.6 Hz likewise). The string's modes,
// read from each shape alone, are the whole eigenbasis' (as string_mode_frequency()'s nearest).
TEST(StringModeFrequencies, AreTheWholeEigenbasisStringModesOnAMirrorSymmetricString) {
    struct Bridges {
        double mass_ratio, resonance;
    };
    for (const Bridges& b :
         {Bridges{0.3, 158.4893192461098}, Bridges{1.0, 441.5704473532985}, Bridges{20.0, 20.0}}) {
        BowedStringOptions o;
        o.pitch = 220, o.body = "none", o.bridge_mass_ratio = b.mass_ratio,
        o.bridge_frequency = b.resonance;
        const Model model = undamped_tuned_string(o, 150);
        const StringElements string = string_elements(150);
        const std::vector<double> expected = string_modes_of_the_eigenbasis(model, string);
        EXPECT_EQ(string_mode_frequencies(model, string), expected)
            << "bridges of " << b.mass_ratio;
        for (double f : {expected[0], expected[1], expected[2], 2000.0})
            EXPECT_EQ(string_mode_frequency(model, string, f),
                      string_mode_decay(model, string, f).frequency)
                << "bridges of " << b.mass_ratio << ", near " << f << " Hz";
    }
}

}  // namespace
}  // namespace archet
