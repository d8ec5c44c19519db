// One root of the scheme's update found near a guess (what a string's tuning looks at) against
// the dense solve of all of them, and the tuning that uses it: its string's first mode on the
// pitch, and the roots it hands on those of the string it leaves.

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <string>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/update_root_near.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/builders/string_chain.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/linear_system.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

using Complex = std::complex<double>;

Complex on_the_circle(double frequency, double dt) {
    return std::polar(1.0, 2.0 * std::numbers::pi * frequency * dt);
}

Complex nearest(const UpdateRoots& all, Complex to) {
    Complex best{std::numeric_limits<double>::infinity()};
    for (const Complex& z : all.roots)
        if (std::abs(z - to) < std::abs(best - to)) best = z;
    return best;
}

// Within a few roundings of the dense solve (whose roots, near 1 for a low mode, are exact to
// about |z|·ε): the frequency to a part in 10¹², a hundredth of what the tuning asks.
void expect_the_dense_root(const LinearSystem& system, const UpdateRoots& all, double frequency,
                           const std::string& what) {
    const auto z = update_root_near(system, on_the_circle(frequency, system.dt));
    ASSERT_TRUE(z.has_value()) << what;
    const Complex dense = nearest(all, *z);
    EXPECT_EQ(dense, nearest(all, on_the_circle(frequency, system.dt)))
        << what << ": it found the root nearest the guess";
    EXPECT_LT(std::abs(*z - dense), 1e-13) << what;
    EXPECT_NEAR(root_frequency(*z, system.dt) / root_frequency(dense, system.dt), 1.0, 1e-12)
        << what;
}

TEST(UpdateRootNear, IsTheDenseSolvesRootNearestTheGuess) {
    // A string with its body (links beyond neighbours: the sparse LU), a bare chain with heavy
    // damped bridges (tridiagonal), and the paper's chaplet (link damping alone); the first
    // partials, where a tuning looks, and a high one.
    for (const std::string name :
         {"bowed-string-220", "bowed-string-440-harmonic", "bowed-string-110-paper"}) {
        const Model model = load_model_file(test::resource("models/" + name + ".json"));
        const LinearSystem system = assemble_linear_system(model, "audio");
        const UpdateRoots all = update_roots(system);
        ASSERT_TRUE(all.converged) << name;
        const double pitch = std::stod(name.substr(std::string("bowed-string-").size(), 3));
        for (const double partial : {1.0, 2.0, 3.0, 9.0}) {
            const double f = pitch * partial;
            expect_the_dense_root(system, all, f, name + " near " + std::to_string(f) + " Hz");
        }
    }
}

TEST(UpdateRootNear, LeavesAFingeredStringToTheDenseSolve) {
    BowedStringOptions o;
    o.pitch = 440, o.masses = 40, o.finger = true, o.finger_position = 0.75, o.with_gesture = false;
    const LinearSystem system = assemble_linear_system(build_bowed_string(o), "audio");
    ASSERT_FALSE(system.fingers.empty());
    EXPECT_FALSE(update_root_near(system, on_the_circle(440, system.dt)).has_value());
}

TEST(RetuneDamped, PutsTheFirstModeOnThePitchAndHandsOnTheRootsOfTheStringItLeaves) {
    for (const double pitch : {110.0, 196.0}) {
        BowedStringOptions o;
        o.pitch = pitch;
        const int n = 80;
        Model model = tuned_string(o, n);
        const UpdateRoots roots = retune_damped(model, o, n);
        const LinearSystem leaves = assemble_linear_system(model, "audio");
        EXPECT_TRUE(identical(roots.system, leaves)) << pitch << " Hz";
        const UpdateRoots solved = update_roots(leaves);
        ASSERT_EQ(roots.roots.size(), solved.roots.size());
        EXPECT_TRUE(roots.roots == solved.roots) << pitch << " Hz: the dense solve's, to the bit";
        double nearest_f = 0;
        for (const DiscreteMode& m : discrete_modes(roots))
            if (std::abs(m.frequency - pitch) < std::abs(nearest_f - pitch))
                nearest_f = m.frequency;
        EXPECT_LT(std::abs(nearest_f / pitch - 1.0), 1e-10) << pitch << " Hz";
    }
}

}  // namespace
}  // namespace archet
