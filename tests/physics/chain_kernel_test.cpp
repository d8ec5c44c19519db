// The chain loop against the scheme it computes, lane by lane: every build this CPU runs
// (plain, AVX2, AVX-512) must give the scalar scheme's bits, for every length of chain (its
// last vector runs past the last MAT), with and without rest lengths and grounds (folded into
// the update), and where it broadcasts the coefficients of a run of alike MATs; and the arrays
// it runs over start MAT 1 on a cache line, so that its whole-vector loads never straddle two.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

#include "archet/builders/bowed_string.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/simulation.hpp"
#include "archet/physics/uniform_span.hpp"
#include "archet/physics/unlinked_runs.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

// A level of n MATs with random motion and coefficients; links 0 and n and the padding MATs
// are zero, as compile() leaves them.
CompiledLevel random_level(int n, bool lengths, bool grounds, std::mt19937_64& random) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    CompiledLevel lv;
    lv.size = n;
    const int storage = n + 2;
    for (auto& b : lv.buffer) b.assign(storage + CompiledLevel::kReadAhead, 0.0);
    for (auto* v : {&lv.coeff, &lv.chain_k, &lv.chain_zdt, &lv.chain_length, &lv.ground_k,
                    &lv.ground_zdt, &lv.ground_rest, &lv.update_x, &lv.update_xp, &lv.update_rest})
        v->assign(storage + CompiledLevel::kReadAhead, 0.0);
    lv.mass.assign(storage, 0.0);
    lv.dt = 1.0 / 48000;
    for (int s = 1; s <= n; ++s) {
        lv.buffer[0][s] = 1e-3 * u(random), lv.buffer[2][s] = 1e-3 * u(random);
        lv.mass[s] = 1e-5 * (1.5 + u(random));
        lv.coeff[s] = lv.dt * lv.dt / lv.mass[s];
        if (grounds) {
            lv.ground_k[s] = 100 * (1.5 + u(random));
            lv.ground_zdt[s] = 10 * (1.5 + u(random));
            lv.ground_rest[s] = 1e-4 * u(random);
            lv.grounds.push_back({s, -1});
        }
    }
    for (int j = 1; j < n; ++j) {
        lv.chain_k[j] = 1e4 * (1.5 + u(random));
        lv.chain_zdt[j] = 1e2 * (1.5 + u(random));
        if (lengths) lv.chain_length[j] = 1e-3 * u(random);
    }
    lv.has_chain_lengths = lengths;
    lv.current = 0;  // x = buffer 0, x⁻ = buffer 2, x⁺ = buffer 1
    fold_grounds(lv);
    return lv;
}

// The scheme, one MAT at a time, in the order the physics documents.
std::vector<double> scheme(const CompiledLevel& lv, std::vector<double>& forces) {
    const double* x = lv.buffer[0].data();
    const double* xp = lv.buffer[2].data();
    auto link = [&](int j) {
        const double d = x[j] - x[j + 1], dp = xp[j] - xp[j + 1];
        return lv.chain_k[j] * (d - lv.chain_length[j]) + lv.chain_zdt[j] * (d - dp);
    };
    std::vector<double> xn(lv.size + 2, 0.0);
    forces.assign(lv.size + 2, 0.0);
    forces[0] = link(0);
    for (int s = 1; s <= lv.size; ++s) {
        forces[s] = link(s);
        const double c = lv.coeff[s], moved = c * (forces[s - 1] - forces[s]);
        if (!grounds_in_chain_loop(lv)) {
            xn[s] = 2.0 * x[s] - xp[s] + moved;
            continue;
        }
        // The ground folded into the update (fold_ground()).
        const double k = lv.ground_k[s], z = lv.ground_zdt[s];
        const double a = (2.0 - c * k) - c * z, b = c * z - 1.0, e = c * k * lv.ground_rest[s];
        xn[s] = ((a * x[s] + b * xp[s]) + e) + moved;
    }
    return xn;
}

// The folded update (fold_ground(), grounded_update()) is the scheme's update with the ground
// subtracted, up to rounding: a few units in the last place of the largest term, over the
// motions and the stable grounds (T²/m·K below 4) of every scale the models use.
TEST(ChainKernel, TheFoldedGroundIsTheGroundUpToRounding) {
    std::mt19937_64 random(42);
    std::uniform_real_distribution<double> u(-1.0, 1.0), decades(-7.0, 0.3);
    CompiledLevel lv = random_level(1, false, true, random);
    for (int trial = 0; trial < 100000; ++trial) {
        const double x = 1e-3 * u(random), xp = x + 1e-6 * u(random);
        const double c = 1e-6 * (1.5 + u(random));             // T²/m
        const double k = std::pow(10.0, decades(random)) / c;  // T²/m·K from 1e-7 to 2
        const double z = 0.25 * std::pow(10.0, decades(random)) / c;
        const double rest = 1e-4 * u(random), forces = 1e2 * u(random);
        lv.coeff[1] = c, lv.ground_k[1] = k, lv.ground_zdt[1] = z, lv.ground_rest[1] = rest;
        fold_ground(lv, 1);
        const double folded = grounded_update(x, xp, lv.update_x[1], lv.update_xp[1],
                                              lv.update_rest[1], c, forces, 0.0);
        const double unfolded = (2.0 * x - xp + c * forces) - c * (k * (x - rest) + z * (x - xp));
        const double largest = std::max(
            {std::abs(2.0 * x), std::abs(xp), std::abs(c * forces), std::abs(lv.update_rest[1])});
        ASSERT_NEAR(folded, unfolded, 8 * std::numeric_limits<double>::epsilon() * largest)
            << "x=" << x << " x⁻=" << xp << " T²/m·K=" << c * k << " T²/m·Z/T=" << c * z;
    }
}

// One build on one random level: every MAT's new position is the scheme's, to the bit, and
// so is the force of each link that the step computes again beside the loop; the padding
// stays zero.
void expect_schemes_bits(ChainBuild build, int n, bool lengths, bool grounds,
                         std::mt19937_64& random) {
    CompiledLevel lv = random_level(n, lengths, grounds, random);
    std::vector<double> forces;
    const std::vector<double> expected = scheme(lv, forces);
    integrate_chain(lv, lv.buffer[1].data(), build);
    SCOPED_TRACE(std::string(chain_build_name(build)) + " n=" + std::to_string(n) +
                 (lengths ? " lengths" : "") + (grounds ? " grounds" : ""));
    for (int s = 1; s <= n; ++s) {
        ASSERT_EQ(std::memcmp(&expected[s], &lv.buffer[1][s], 8), 0)
            << "MAT " << s << ": " << expected[s] << " vs " << lv.buffer[1][s];
        const double f = chain_link_force(lv, lv.buffer[0].data(), lv.buffer[2].data(), s);
        ASSERT_EQ(std::memcmp(&forces[s], &f, 8), 0) << "link " << s;
    }
    // The padding and the zeros after it stay zero: the last vector ran into them.
    for (std::size_t s = n + 1; s < lv.buffer[1].size(); ++s)
        ASSERT_EQ(lv.buffer[1][s], 0.0) << "storage " << s;
}

TEST(ChainKernel, EveryBuildGivesTheSchemesBitsForEveryLength) {
    std::mt19937_64 random(20261202);
    int builds_run = 0;
    for (ChainBuild build : {ChainBuild::Plain, ChainBuild::Avx2, ChainBuild::Avx512}) {
        if (!chain_build_runs_here(build)) {
            std::printf("[ note ] the %s build does not run on this CPU\n",
                        chain_build_name(build));
            continue;
        }
        ++builds_run;
        for (int n : {1, 2, 3, 5, 7, 8, 9, 15, 16, 17, 31, 33, 64, 67, 1000})
            for (bool lengths : {false, true})
                for (bool grounds : {false, true})
                    expect_schemes_bits(build, n, lengths, grounds, random);
    }
    EXPECT_GE(builds_run, 1);
    EXPECT_TRUE(chain_build_runs_here(chosen_chain_build()));
}

// MATs first … last given MAT first's coefficients (T²/m, ground, the chain link after it), as
// a homogeneous string has them, and the run found as compile() finds it.
void make_alike(CompiledLevel& lv, int first, int last) {
    for (int s = first + 1; s <= last; ++s) {
        lv.coeff[s] = lv.coeff[first], lv.mass[s] = lv.mass[first];
        lv.ground_k[s] = lv.ground_k[first], lv.ground_zdt[s] = lv.ground_zdt[first];
        lv.ground_rest[s] = lv.ground_rest[first];
        lv.chain_k[s] = lv.chain_k[first], lv.chain_zdt[s] = lv.chain_zdt[first];
        lv.chain_length[s] = lv.chain_length[first];
    }
    fold_grounds(lv);
    find_uniform_runs(lv);
}

// The loop runs the rounds before a run of alike MATs, those wholly inside it (broadcast), and
// those after: together exactly the rounds s = 1, 1 + W, … ≤ n of the plain loop, in order,
// for every width, chain length and run (empty and short ones too), on any CPU.
TEST(ChainKernel, SharedRoundsAreTheRoundsWhollyInsideTheRun) {
    for (int W : {2, 4, 8})
        for (int n = 0; n <= 40; ++n)
            for (int first = 1; first <= n + 1; ++first)
                for (int last = first - 1; last <= n; ++last) {
                    const SharedRounds shared = shared_rounds(first, last, W);
                    std::vector<int> ran, inside;
                    for (int s = 1; s < shared.begin; s += W) ran.push_back(s);
                    for (int s = shared.begin; s < shared.end; s += W) ran.push_back(s);
                    for (int s = shared.begin; s < shared.end; s += W) inside.push_back(s);
                    for (int s = shared.end; s < n + 1; s += W) ran.push_back(s);
                    std::vector<int> expected_ran, expected_inside;
                    for (int s = 1; s <= n; s += W) {
                        expected_ran.push_back(s);
                        if (s >= first && s + W - 1 <= last) expected_inside.push_back(s);
                    }
                    const std::string where = "W=" + std::to_string(W) + " n=" + std::to_string(n) +
                                              " run " + std::to_string(first) + "…" +
                                              std::to_string(last);
                    ASSERT_EQ(ran, expected_ran) << where;
                    ASSERT_EQ(inside, expected_inside) << where;
                }
}

int lanes(ChainBuild build) {
    return build == ChainBuild::Avx512 ? 8 : build == ChainBuild::Avx2 ? 4 : 2;
}

// The rounds inside a run of alike MATs broadcast the coefficients they share: the same bits
// as reading them, wherever the run starts and ends against the rounds of each build. Their
// arrays are spoilt with NaN once the run is found, so a round that read them would show it.
TEST(ChainKernel, ARunOfAlikeMatsGivesTheSchemesBits) {
    std::mt19937_64 random(7);
    int runs = 0, broadcast_rounds = 0;
    for (ChainBuild build : {ChainBuild::Plain, ChainBuild::Avx2, ChainBuild::Avx512}) {
        if (!chain_build_runs_here(build)) continue;
        for (int n : {3, 9, 16, 40, 67, 200})
            for (auto [first, last] : {std::pair{1, n - 1},
                                       {2, n - 1},
                                       {1, 9},
                                       {3, 12},
                                       {9, 24},
                                       {5, n - 3},
                                       {n / 2, n / 2 + 3}})
                for (bool lengths : {false, true})
                    for (bool grounds : {false, true}) {
                        // Link n is the padding's, zero.
                        if (last >= n || last <= first) continue;
                        CompiledLevel lv = random_level(n, lengths, grounds, random);
                        make_alike(lv, first, last);
                        SCOPED_TRACE(std::string(chain_build_name(build)) +
                                     " n=" + std::to_string(n) + " run " + std::to_string(first) +
                                     "…" + std::to_string(last) + (lengths ? " lengths" : "") +
                                     (grounds ? " grounds" : ""));
                        // A run too short to hold a round of eight is not kept.
                        const bool kept = last - first + 1 >= UniformRuns::kShortest;
                        ASSERT_EQ(lv.uniform.count(), kept ? 1 : 0);
                        if (kept) {
                            ASSERT_EQ(lv.uniform[0].first, first);
                            ASSERT_EQ(lv.uniform[0].last, last);
                        }
                        std::vector<double> forces;
                        const std::vector<double> expected = scheme(lv, forces);
                        const SharedRounds shared =
                            kept ? shared_rounds(first, last, lanes(build)) : SharedRounds{1, 1};
                        const double nan = std::numeric_limits<double>::quiet_NaN();
                        for (int s = shared.begin; s < shared.end; ++s)
                            for (auto* a : {&lv.coeff, &lv.chain_k, &lv.chain_zdt, &lv.chain_length,
                                            &lv.update_x, &lv.update_xp, &lv.update_rest})
                                (*a)[s] = nan;
                        broadcast_rounds += (shared.end - shared.begin) / lanes(build);
                        integrate_chain(lv, lv.buffer[1].data(), build);
                        for (int s = 1; s <= n; ++s)
                            ASSERT_EQ(std::memcmp(&expected[s], &lv.buffer[1][s], 8), 0)
                                << "MAT " << s << ": " << expected[s] << " vs " << lv.buffer[1][s];
                        for (std::size_t s = n + 1; s < lv.buffer[1].size(); ++s)
                            ASSERT_EQ(lv.buffer[1][s], 0.0) << "storage " << s;
                        ++runs;
                    }
    }
    EXPECT_GT(runs, 0);
    EXPECT_GT(broadcast_rounds, 100);
}

// The stored energy reads the run's coefficients once, and leaves out the terms a zero one
// makes vanish (no rest length, no spring or no damper to ground): the same bits as summing
// every MAT from the arrays, which are spoilt with NaN where the run's rounds of eight lie.
TEST(ChainKernel, ARunOfAlikeMatsStoresTheSameEnergy) {
    std::mt19937_64 random(5);
    int sums = 0;
    for (ChainBuild build : {ChainBuild::Plain, ChainBuild::Avx2, ChainBuild::Avx512}) {
        if (!chain_build_runs_here(build)) continue;
        for (int n : {9, 16, 40, 67, 200})
            for (auto [first, last] : {std::pair{1, n - 1},
                                       {2, n - 1},
                                       {3, 12},
                                       {9, 24},
                                       {5, n - 3},
                                       {n / 2, n / 2 + 3}})
                for (int terms = 0; terms < 8; ++terms) {
                    if (last >= n || last <= first) continue;
                    const bool length = terms & 4, spring = terms & 2, damper = terms & 1;
                    CompiledLevel lv = random_level(n, length, true, random);
                    if (!spring) lv.ground_k[first] = 0.0;
                    if (!damper) lv.ground_zdt[first] = 0.0;
                    make_alike(lv, first, last);
                    SCOPED_TRACE(std::string(chain_build_name(build)) + " n=" + std::to_string(n) +
                                 " run " + std::to_string(first) + "…" + std::to_string(last) +
                                 " terms " + std::to_string(terms));
                    const UniformRuns runs = lv.uniform;
                    lv.uniform = UniformRuns{};
                    const double expected = level_stored_energy(lv, build);
                    lv.uniform = runs;
                    const SharedRounds shared = shared_rounds(first, last, 8);
                    for (int s = shared.begin; s < shared.end; ++s)
                        for (auto* a : {&lv.mass, &lv.chain_k, &lv.chain_zdt, &lv.chain_length,
                                        &lv.ground_k, &lv.ground_zdt, &lv.ground_rest})
                            (*a)[s] = std::numeric_limits<double>::quiet_NaN();
                    const double energy = level_stored_energy(lv, build);
                    ASSERT_EQ(std::memcmp(&expected, &energy, 8), 0)
                        << expected << " vs " << energy;
                    sums += shared.begin < shared.end;
                }
    }
    EXPECT_GT(sums, 50);
}

using Spans = std::vector<std::pair<int, int>>;

// The level's runs, first … last each.
Spans spans(const CompiledLevel& lv) {
    Spans out;
    for (const UniformSpan& run : lv.uniform.all()) out.emplace_back(run.first, run.last);
    return out;
}

// A MAT changed while playing splits its run: each side stays a run while it is long enough to
// hold a round, with the run's coefficients; a change that leaves the MAT alike, or a MAT
// outside every run, changes nothing.
TEST(ChainKernel, AChangedMatSplitsItsRun) {
    std::mt19937_64 random(11);
    CompiledLevel lv = random_level(60, false, true, random);
    make_alike(lv, 3, 50);
    const ChainCoefficients shared = lv.uniform[0].shared;
    auto change = [&](int s, double coeff) {
        lv.coeff[s] = coeff;
        fold_ground(lv, s);
        split_uniform_run(lv, s);
        return spans(lv);
    };
    EXPECT_EQ(change(20, shared.c), (Spans{{3, 50}}));      // alike still
    EXPECT_EQ(change(55, 2 * shared.c), (Spans{{3, 50}}));  // outside the run
    EXPECT_EQ(change(30, 2 * shared.c), (Spans{{3, 29}, {31, 50}}));
    EXPECT_EQ(change(10, 2 * shared.c), (Spans{{11, 29}, {31, 50}}));
    EXPECT_EQ(change(45, 2 * shared.c), (Spans{{11, 29}, {31, 44}}));  // 46…50: too short
    EXPECT_EQ(change(35, 2 * shared.c), (Spans{{11, 29}, {36, 44}}));
    EXPECT_EQ(change(40, 2 * shared.c), (Spans{{11, 29}}));
    EXPECT_EQ(change(11, 2 * shared.c), (Spans{{12, 29}}));  // a run's first MAT
    EXPECT_EQ(change(29, 2 * shared.c), (Spans{{12, 28}}));  // and its last
    for (const UniformSpan& run : lv.uniform.all()) EXPECT_TRUE(run.shared == shared);
    // Compiled again (or a state loaded), the runs are found afresh: the same ones.
    find_uniform_runs(lv);
    EXPECT_EQ(spans(lv), (Spans{{12, 28}}));
    make_alike(lv, 1, 59);
    EXPECT_EQ(spans(lv), (Spans{{1, 59}}));
}

// Each string of a level (an instrument of several) has its own run; when there are more than
// the runs a level keeps, the longest are kept, in order, and a split with no room for both
// sides keeps the longer one.
TEST(ChainKernel, EachStringHasItsOwnRunAndTheLongestAreKept) {
    std::mt19937_64 random(13);
    CompiledLevel lv = random_level(300, true, true, random);
    const Spans strings{{1, 20},    {22, 30},   {32, 60},   {62, 71},   {73, 120}, {122, 130},
                        {132, 150}, {152, 190}, {192, 240}, {242, 249}, {251, 299}};
    for (auto [first, last] : strings) make_alike(lv, first, last);
    ASSERT_GT(strings.size(), static_cast<std::size_t>(UniformRuns::kCapacity));
    // Of lengths 20, 9, 29, 10, 48, 9, 19, 39, 49, 8, 49: the two of 9 and the one of 8 go.
    EXPECT_EQ(spans(lv), (Spans{{1, 20},
                                {32, 60},
                                {62, 71},
                                {73, 120},
                                {132, 150},
                                {152, 190},
                                {192, 240},
                                {251, 299}}));
    const ChainCoefficients shared = lv.uniform[3].shared;
    lv.chain_k[90] *= 2;
    split_uniform_run(lv, 90);
    EXPECT_EQ(spans(lv)[3], std::pair(91, 120));
    EXPECT_TRUE(lv.uniform[3].shared == shared);
    // Of as long runs, the first ones are kept.
    CompiledLevel alike = random_level(120, false, true, random);
    for (int first = 1; first < 110; first += 11) make_alike(alike, first, first + 9);
    EXPECT_EQ(
        spans(alike),
        (Spans{{1, 10}, {12, 21}, {23, 32}, {34, 43}, {45, 54}, {56, 65}, {67, 76}, {78, 87}}));
}

// Several runs in one level, with coefficients of their own: every build gives the scheme's
// bits and the stored energy the same bits as summing the arrays, which are spoilt with NaN
// wherever a run's rounds lie.
TEST(ChainKernel, SeveralRunsGiveTheSchemesBits) {
    std::mt19937_64 random(17);
    int checked = 0;
    for (ChainBuild build : {ChainBuild::Plain, ChainBuild::Avx2, ChainBuild::Avx512}) {
        if (!chain_build_runs_here(build)) continue;
        for (bool lengths : {false, true})
            for (bool grounds : {false, true})
                for (const Spans& layout :  // apart, adjacent, from MAT 1, of eight, to the end
                     {Spans{{2, 30}, {31, 47}, {50, 58}, {70, 119}},
                      Spans{{1, 8}, {9, 16}, {17, 24}, {25, 119}},
                      Spans{{3, 11}, {12, 20}, {60, 68}, {100, 119}}}) {
                    CompiledLevel lv = random_level(120, lengths, grounds, random);
                    for (auto [first, last] : layout) make_alike(lv, first, last);
                    ASSERT_EQ(spans(lv), layout);
                    std::vector<double> forces;
                    const std::vector<double> expected = scheme(lv, forces);
                    CompiledLevel read_all = lv;
                    read_all.uniform = UniformRuns{};
                    const double expected_energy = level_stored_energy(read_all, build);
                    CompiledLevel for_energy = lv;
                    const double nan = std::numeric_limits<double>::quiet_NaN();
                    for (const UniformSpan& run : lv.uniform.all()) {
                        const SharedRounds loop = shared_rounds(run.first, run.last, lanes(build));
                        for (int s = loop.begin; s < loop.end; ++s)
                            for (auto* a : {&lv.coeff, &lv.chain_k, &lv.chain_zdt, &lv.chain_length,
                                            &lv.update_x, &lv.update_xp, &lv.update_rest})
                                (*a)[s] = nan;
                        const SharedRounds sum = shared_rounds(run.first, run.last, 8);
                        for (int s = sum.begin; s < sum.end; ++s)
                            for (auto* a :
                                 {&for_energy.mass, &for_energy.chain_k, &for_energy.chain_zdt,
                                  &for_energy.chain_length, &for_energy.ground_k,
                                  &for_energy.ground_zdt, &for_energy.ground_rest})
                                (*a)[s] = nan;
                    }
                    SCOPED_TRACE(std::string(chain_build_name(build)) +
                                 (lengths ? " lengths" : "") + (grounds ? " grounds" : ""));
                    integrate_chain(lv, lv.buffer[1].data(), build);
                    for (int s = 1; s <= lv.size; ++s)
                        ASSERT_EQ(std::memcmp(&expected[s], &lv.buffer[1][s], 8), 0) << "MAT " << s;
                    const double energy = level_stored_energy(for_energy, build);
                    ASSERT_EQ(std::memcmp(&expected_energy, &energy, 8), 0)
                        << expected_energy << " vs " << energy;
                    ++checked;
                }
    }
    EXPECT_GT(checked, 0);
}

// The level's stored energy, summed MAT by MAT in one chain of additions: the sum the
// lanes must reproduce up to rounding.
double serial_energy(const CompiledLevel& lv) {
    const double* x = lv.buffer[0].data();
    const double* xp = lv.buffer[2].data();
    double e = 0;
    for (int s = 1; s <= lv.size; ++s) {
        const double v = (x[s] - xp[s]) / lv.dt;
        const double d = x[s] - x[s + 1] - lv.chain_length[s];
        const double dp = xp[s] - xp[s + 1] - lv.chain_length[s];
        const double u = d - dp, g = x[s] - xp[s], rest = lv.ground_rest[s];
        e += 0.5 * lv.mass[s] * v * v + 0.5 * lv.chain_k[s] * d * dp -
             0.25 * lv.chain_zdt[s] * u * u +
             0.5 * lv.ground_k[s] * (x[s] - rest) * (xp[s] - rest) -
             0.25 * lv.ground_zdt[s] * g * g;
    }
    return e;
}

TEST(ChainKernel, EveryBuildSumsTheSameStoredEnergy) {
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> u(0.5, 1.5);
    for (int n : {1, 7, 8, 9, 17, 64, 67, 1000}) {
        CompiledLevel lv = random_level(n, true, true, random);
        for (int s = 1; s <= n; ++s) lv.mass[s] = 1e-5 * u(random);
        const double plain = level_stored_energy(lv, ChainBuild::Plain);
        EXPECT_NEAR(plain, serial_energy(lv), 1e-12 * std::abs(serial_energy(lv))) << "n=" << n;
        for (ChainBuild build : {ChainBuild::Avx2, ChainBuild::Avx512})
            if (chain_build_runs_here(build)) {
                const double wide = level_stored_energy(lv, build);
                EXPECT_EQ(std::memcmp(&wide, &plain, sizeof wide), 0)
                    << chain_build_name(build) << " n=" << n << ": " << wide << " vs " << plain;
            }
    }
}

// Every array the chain loop and the energy sum read, MAT 1 on a 64-byte line, as compiled,
// copied (the engine compiles a copy for the real-time thread) and moved into a Simulation.
void expect_mat1_on_a_line(const CompiledModel& model, const std::string& where) {
    for (const CompiledLevel& lv : model.levels) {
        std::vector<const MatArray*> arrays{&lv.coeff,      &lv.mass,         &lv.chain_k,
                                            &lv.chain_zdt,  &lv.chain_length, &lv.ground_k,
                                            &lv.ground_zdt, &lv.ground_rest,  &lv.update_x,
                                            &lv.update_xp,  &lv.update_rest};
        for (const MatArray& b : lv.buffer) arrays.push_back(&b);
        for (const MatArray* a : arrays)
            EXPECT_EQ(reinterpret_cast<std::uintptr_t>(a->data() + 1) % 64, 0u)
                << where << ", level " << lv.id;
    }
}

TEST(ChainKernel, TheArraysItRunsOverStartMat1OnACacheLine) {
    const CompiledModel compiled =
        compile(load_model_file(test::resource("models/bowed-string-110.json")));
    expect_mat1_on_a_line(compiled, "compiled");
    const CompiledModel copy = compiled;
    expect_mat1_on_a_line(copy, "copied");
    Simulation sim{CompiledModel(compiled)};
    Simulation moved = std::move(sim);
    expect_mat1_on_a_line(moved.model(), "moved into a simulation");
}

// A chain of `masses` between two fixed ends, plucked, with `anchors` more fixed MATs linked
// on after the last end: the fixed MATs stored last, off their rest so that a zero would show.
Model chain_with_fixed_tail(int masses, int anchors) {
    Model model = test::chain(masses, 1e-3, 1e3, 0.01);
    model.find_mat("end_b")->position = 0.002;
    model.find_mat("m1")->position = 0.001;
    std::string last = "end_b";
    for (int a = 1; a <= anchors; ++a) {
        const std::string anchor = "anchor" + std::to_string(a);
        model.mats.push_back(test::fixed(anchor, 0.002 + 0.001 * a));
        model.lias.push_back(test::spring_damper("to_" + anchor, last, anchor, 1e3, 0.01));
        last = anchor;
    }
    validate_model(model);
    return model;
}

// Steps a level's chain loop alone with `build`, as step() runs it.
void step_chain(CompiledLevel& level, ChainBuild build) {
    integrate_chain(level, level.x_next(), build);
    level.current = CompiledLevel::after(level.current);
}

// A fixed MAT at the end of the storage (a bow's surface, a nut) is left out of the chain
// loop: it must hold its position in the buffer the loop would have written, from the first
// step on, and the masses beside it move as they would with the loop passing it, in every
// build (rounds of 8, 4 and 2 MATs from storage 1). Seven masses between two fixed ends put
// the last end at storage 9, where a round of every build starts; six masses and three fixed
// MATs after them end mid-round.
TEST(ChainKernel, LeavesTheFixedMatsAtTheEndOfTheStorageWhereTheyAre) {
    for (const auto& [masses, anchors] : {std::pair{7, 0}, std::pair{6, 2}, std::pair{13, 1}}) {
        const CompiledModel compiled = compile(chain_with_fixed_tail(masses, anchors));
        const CompiledLevel& level = compiled.levels[0];
        ASSERT_EQ(level.fixed_after, 1 + anchors);
        ASSERT_EQ(level.size, masses + 2 + anchors);
        for (ChainBuild build : {ChainBuild::Plain, ChainBuild::Avx2, ChainBuild::Avx512}) {
            if (!chain_build_runs_here(build)) continue;
            SCOPED_TRACE(std::string(chain_build_name(build)) + ", " + std::to_string(masses) +
                         " masses, " + std::to_string(anchors) + " anchors");
            CompiledLevel left_out = level, passed = level;
            passed.fixed_after = 0;  // the loop passing them, as before they were left out
            for (int i = 0; i < 480; ++i) {
                step_chain(left_out, build);
                step_chain(passed, build);
                for (int s = 1; s <= level.size; ++s)
                    ASSERT_EQ(left_out.x()[s], passed.x()[s]) << "MAT " << s << ", step " << i;
            }
            EXPECT_EQ(left_out.x()[masses + 2], 0.002);
            EXPECT_NE(left_out.x()[masses + 1], 0.0) << "the pluck reached the last mass";
        }
    }
}

// A state saved before the chain loop stopped at the fixed MATs (their x[n+1] a zero at the
// start) plays on with them where they are.
TEST(ChainKernel, AStateSavedBeforeHoldsTheFixedMatsWhereTheyAre) {
    const Model model = chain_with_fixed_tail(7, 0);
    Simulation before(compile(model));
    CompiledLevel& level = before.model().levels[0];
    level.x_next()[level.size] = 0.0;  // as compile() left it then
    std::vector<double> state(before.state_size());
    before.save_state(state.data());
    Simulation loaded(compile(model));
    loaded.load_state(state.data());
    const MatSlot end = loaded.model().mat_slots.at("end_b");
    for (int i = 0; i < 48; ++i) {
        loaded.step();
        ASSERT_EQ(loaded.position(end), 0.002) << "step " << i;
    }
}

// Unlinked MATs: chain links absent on both sides of first … last (no element behind them,
// zero coefficients), every other link standing for an element, and the runs found as compile()
// finds them.
void make_unlinked(CompiledLevel& lv, const Spans& unlinked) {
    lv.chain_element.assign(lv.size + 2, 0);
    lv.chain_element[0] = lv.chain_element[lv.size] = -1;  // the padding's links
    for (auto [first, last] : unlinked)
        for (int j = first - 1; j <= last; ++j) {
            lv.chain_k[j] = lv.chain_zdt[j] = lv.chain_length[j] = 0.0;
            lv.chain_element[j] = -1;
        }
    fold_grounds(lv);
    lv.unlinked = find_unlinked_runs(lv);
    find_uniform_runs(lv);
}

Spans unlinked_spans(const CompiledLevel& lv) {
    Spans out;
    for (const UnlinkedRun& run : lv.unlinked) out.emplace_back(run.first, run.last);
    return out;
}

// The rounds wholly inside an unlinked run move their MATs by their own update alone, and give
// the scheme's bits: with the T²/m of those MATs made NaN (which the chain's update would
// spread), and with MATs at rest exactly at +0 and −0, whose links' forces are zeros of either
// sign. Runs of alike MATs and unlinked runs share the loop, each MAT taken one way: an unlinked
// run of alike MATs is in no run of alike MATs.
TEST(ChainKernel, UnlinkedRunsGiveTheSchemesBits) {
    std::mt19937_64 random(2026);
    int checked = 0;
    for (ChainBuild build : {ChainBuild::Plain, ChainBuild::Avx2, ChainBuild::Avx512}) {
        if (!chain_build_runs_here(build)) continue;
        for (bool lengths : {false, true})
            for (const Spans& layout : {Spans{{20, 60}}, Spans{{1, 40}}, Spans{{9, 40}, {60, 120}},
                                        Spans{{3, 36}, {70, 101}}}) {
                CompiledLevel lv = random_level(120, lengths, true, random);
                make_alike(lv, 40, 90);           // across an unlinked run's end, or inside one
                for (int s = 31; s <= 38; ++s) {  // at rest exactly, at zeros of both signs
                    lv.ground_rest[s] = 0.0;
                    lv.buffer[0][s] = s % 2 ? -0.0 : 0.0, lv.buffer[2][s] = s % 4 < 2 ? -0.0 : 0.0;
                }
                make_unlinked(lv, layout);
                ASSERT_EQ(unlinked_spans(lv), layout);
                const int short_first = layout.back().first == 70 ? 50 : -1;
                if (short_first > 0) {  // fewer than UnlinkedRun::kShortest: in no run
                    make_unlinked(lv, {layout[0], {short_first, short_first + 10}, layout[1]});
                    ASSERT_EQ(unlinked_spans(lv), layout);
                }
                for (const UnlinkedRun& run : lv.unlinked) {
                    ASSERT_TRUE(run.moves_alone());
                    for (const UniformSpan& alike : lv.uniform.all())
                        ASSERT_TRUE(alike.last < run.first || run.last < alike.first)
                            << "alike " << alike.first << "…" << alike.last;
                }
                std::vector<double> forces;
                const std::vector<double> expected = scheme(lv, forces);
                const double nan = std::numeric_limits<double>::quiet_NaN();
                for (const UnlinkedRun& run : lv.unlinked) {
                    const SharedRounds alone = run.rounds(lanes(build));
                    for (int s = alone.begin; s < alone.end; ++s) lv.coeff[s] = nan;
                }
                SCOPED_TRACE(std::string(chain_build_name(build)) + (lengths ? " lengths" : ""));
                integrate_chain(lv, lv.buffer[1].data(), build);
                for (int s = 1; s <= lv.size; ++s)
                    ASSERT_EQ(std::memcmp(&expected[s], &lv.buffer[1][s], 8), 0)
                        << "MAT " << s << ": " << expected[s] << " vs " << lv.buffer[1][s];
                ++checked;
            }
    }
    EXPECT_GT(checked, 0);
}

// Every build this CPU runs, each on a copy of `lv`, gives every MAT's `expected` position to
// the bit.
void expect_every_build_gives(const CompiledLevel& lv, const std::vector<double>& expected) {
    for (ChainBuild build : {ChainBuild::Plain, ChainBuild::Avx2, ChainBuild::Avx512}) {
        if (!chain_build_runs_here(build)) continue;
        SCOPED_TRACE(chain_build_name(build));
        CompiledLevel level = lv;
        integrate_chain(level, level.buffer[1].data(), build);
        for (int s = 1; s <= lv.size; ++s)
            ASSERT_EQ(std::memcmp(&expected[s], &level.buffer[1][s], 8), 0) << "MAT " << s;
    }
}

// A MAT at −0 whose ground folds to an e of −0 (a rest of −0) has an own update of −0, where
// the chain's adds the links' +0 and gives +0: its run is then left to the chain's rounds (and
// the loop gives the scheme's +0), and moves alone again once the ground folds to +0.
TEST(ChainKernel, ANegativeZeroOwnUpdateKeepsItsRunInTheChainsRounds) {
    std::mt19937_64 random(7);
    CompiledLevel lv = random_level(64, false, true, random);
    constexpr int kAtRest = 20;
    double* x = lv.buffer[0].data();
    double* xp = lv.buffer[2].data();
    // The links on either side give +0 and −0: 0·d + 0·(d − d⁻) with d > 0, then with d < 0.
    x[kAtRest - 1] = 1e-4, xp[kAtRest - 1] = 0.0;
    x[kAtRest] = -0.0, xp[kAtRest] = 0.0, lv.ground_rest[kAtRest] = -0.0;
    x[kAtRest + 1] = 1e-4, xp[kAtRest + 1] = -1e-4;
    make_unlinked(lv, {{9, 40}});
    ASSERT_EQ(unlinked_spans(lv), (Spans{{9, 40}}));
    ASSERT_EQ(lv.unlinked[0].zero_prone_rests, 1);
    std::vector<double> forces;
    const std::vector<double> expected = scheme(lv, forces);
    ASSERT_TRUE(expected[kAtRest] == 0.0 && !std::signbit(expected[kAtRest]));
    expect_every_build_gives(lv, expected);  // in the chain's rounds
    for (ChainBuild build : {ChainBuild::Plain, ChainBuild::Avx2, ChainBuild::Avx512}) {
        if (!chain_build_runs_here(build)) continue;
        SCOPED_TRACE(chain_build_name(build));
        CompiledLevel alone = lv;  // what moving it alone would give: −0
        alone.unlinked[0].zero_prone_rests = 0;
        integrate_chain(alone, alone.buffer[1].data(), build);
        EXPECT_TRUE(std::signbit(alone.buffer[1][kAtRest]));
    }
    lv.ground_rest[kAtRest] = 0.0;
    fold_ground(lv, kAtRest);
    refolded_unlinked(lv, kAtRest, true);
    EXPECT_TRUE(lv.unlinked[0].moves_alone());
}

// The round after an unlinked run takes, on its left, the force of the link just before it:
// a zero whose sign shows on a MAT at −0 with a rest of −0 (its own update −0) between that
// link's +0 and a link of its own at +0. The link before the run gives −0, which the round
// would add had it carried that force across the run (every build's rounds end at MAT 48).
TEST(ChainKernel, TheRoundAfterAnUnlinkedRunTakesTheForceOfTheLinkBeforeIt) {
    std::mt19937_64 random(3);
    CompiledLevel lv = random_level(64, false, true, random);
    double* x = lv.buffer[0].data();
    double* xp = lv.buffer[2].data();
    x[8] = -1e-4, xp[8] = 0.0, x[9] = 1e-4, xp[9] = 0.0;    // link 8, before the run: −0
    x[48] = 1e-4;                                           // link 48, after it: +0
    x[49] = -0.0, xp[49] = 0.0, lv.ground_rest[49] = -0.0;  // its own update −0
    x[50] = -0.0, xp[50] = 0.0;                             // link 49, its own: +0
    make_unlinked(lv, {{9, 48}});
    ASSERT_EQ(unlinked_spans(lv), (Spans{{9, 48}}));
    ASSERT_TRUE(lv.unlinked[0].moves_alone());
    std::vector<double> forces;
    const std::vector<double> expected = scheme(lv, forces);
    ASSERT_TRUE(std::signbit(forces[8]) && !std::signbit(forces[48]) && !std::signbit(forces[49]));
    ASSERT_TRUE(expected[49] == 0.0 && !std::signbit(expected[49]));
    expect_every_build_gives(lv, expected);
}

// A state is all numbers: one that gives an absent link a stiffness links the MATs on either
// side, and their run is dropped (the loop then takes that link, as the scheme does).
TEST(ChainKernel, AStateThatLinksAnUnlinkedRunDropsIt) {
    std::mt19937_64 random(5);
    CompiledLevel lv = random_level(100, false, true, random);
    make_unlinked(lv, {{10, 45}, {55, 90}});
    lv.chain_k[60] = 1e3;
    recheck_unlinked_runs(lv);
    EXPECT_EQ(unlinked_spans(lv), (Spans{{10, 45}}));
    std::vector<double> forces;
    expect_every_build_gives(lv, scheme(lv, forces));
}

// A bowed string in modal form, its modes moved alone, gives the bits it gives with its modes in
// the chain's rounds, sample for sample and probe for probe, across live changes of a mode's
// ground that give it an e of −0 (a stiffness of 0 with a rest below 0: its run then stays in
// the chain's rounds) and take it back.
TEST(ChainKernel, AModalStringSoundsTheSameWithItsModesMovedAlone) {
    BowedStringOptions o;
    o.structure = Structure::Modal;
    o.masses = 60;
    Model model = build_bowed_string(o);
    model.find_mat("mode3")->position = -1e-9;  // its rest
    const CompiledModel compiled = compile(model);
    ASSERT_EQ(compiled.levels[0].unlinked.size(), 1u);
    const UnlinkedRun run = compiled.levels[0].unlinked[0];
    EXPECT_GE(run.last - run.first + 1, 60) << "every mode is in the run";
    Simulation alone(compiled), in_rounds(compiled);
    in_rounds.model().levels[0].unlinked.clear();
    const auto stiffness = alone.model().resolve_parameter({"mode3", "stiffness"});
    const double k = alone.read_slot(stiffness);
    std::vector<double> a(4800), b(4800);
    for (int part = 0; part < 4; ++part) {
        const double set = part == 1 ? 0.0 : part == 2 ? 0.5 * k : k;
        if (part > 0) alone.write_slot(stiffness, set), in_rounds.write_slot(stiffness, set);
        EXPECT_EQ(alone.model().levels[0].unlinked[0].moves_alone(), part != 1) << "part " << part;
        // A state loaded (a take's, a hand-over's) counts the rests it brings again.
        std::vector<double> state(alone.state_size());
        alone.save_state(state.data());
        Simulation loaded(compiled);
        loaded.load_state(state.data());
        EXPECT_EQ(loaded.model().levels[0].unlinked[0].moves_alone(), part != 1) << "part " << part;
        ASSERT_EQ(alone.run(a), a.size());
        ASSERT_EQ(in_rounds.run(b), b.size());
        ASSERT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0) << "part " << part;
        for (std::size_t p = 0; p < alone.probe_count(); ++p) {
            const double pa = alone.probe(p), pb = in_rounds.probe(p);
            ASSERT_EQ(std::memcmp(&pa, &pb, 8), 0) << "probe " << p;
        }
    }
    EXPECT_GT(*std::max_element(a.begin(), a.end()), 1e-3) << "it was bowed";
}

}  // namespace
}  // namespace archet
