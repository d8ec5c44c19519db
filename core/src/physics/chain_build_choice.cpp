#include "archet/physics/chain_build_choice.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <limits>
#include <vector>

#include "archet/common/denormal_guard.hpp"
#include "archet/physics/simulation.hpp"

namespace archet {

namespace {

constexpr double kTrialSeconds = 2e-4;  ///< each build's run, long enough for the clock
constexpr int kRounds = 5;              ///< the builds alternate; each keeps its fastest run
constexpr std::size_t kFewestTicks = 16, kMostTicks = 4096;

using Clock = std::chrono::steady_clock;

// Seconds for one run of `ticks`, or infinity if it blew up.
double timed_run(Simulation& sim, std::vector<double>& sound, std::size_t ticks, ChainBuild build) {
    const auto start = Clock::now();
    const std::size_t ran = sim.run({sound.data(), ticks}, build);
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return ran == ticks ? seconds : std::numeric_limits<double>::infinity();
}

// Times AVX-512 and AVX2 in alternated runs of about kTrialSeconds, the fastest run of each
// counting, and keeps AVX2 only if it was clearly faster. Plain (SSE2) is never the fastest
// where AVX2 runs.
ChainBuild time_builds(Simulation& sim) {
    constexpr std::array<ChainBuild, 2> kBuilds{ChainBuild::Avx512, ChainBuild::Avx2};
    const DenormalGuard no_denormals;
    std::vector<double> sound(kMostTicks);
    // As many ticks a run as take about kTrialSeconds in the widest build.
    const double per_tick = timed_run(sim, sound, kFewestTicks, kBuilds[0]) / kFewestTicks;
    if (!(per_tick < std::numeric_limits<double>::infinity())) return kBuilds[0];
    const std::size_t ticks =
        std::clamp(static_cast<std::size_t>(kTrialSeconds / std::max(per_tick, 1e-9)), kFewestTicks,
                   kMostTicks);
    std::array<double, 2> fastest{std::numeric_limits<double>::infinity(),
                                  std::numeric_limits<double>::infinity()};
    for (int round = 0; round < kRounds; ++round)
        for (std::size_t b = 0; b < kBuilds.size(); ++b)
            fastest[b] = std::min(fastest[b], timed_run(sim, sound, ticks, kBuilds[b]));
    if (!(fastest[0] < std::numeric_limits<double>::infinity())) return kBuilds[0];
    return fastest[1] < (1.0 - kClearMargin) * fastest[0] ? kBuilds[1] : kBuilds[0];
}

}  // namespace

ChainBuild fastest_chain_build(Simulation& sim) {
    if (!chain_build_runs_here(ChainBuild::Avx512) || !sim.bowed_chain_misfit().empty())
        return chosen_chain_build();
    // The trials run `sim` itself, which then resumes from where they found it: a copy of a
    // 10,000-element model would cost more than the trials.
    std::vector<double> state(sim.state_size());
    sim.save_state(state.data());
    const ChainBuild fastest = time_builds(sim);
    sim.load_state(state.data());
    return fastest;
}

}  // namespace archet
