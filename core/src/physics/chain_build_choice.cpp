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

// Times each build in alternated runs of about kTrialSeconds; the fastest run of each counts.
ChainBuild time_builds(Simulation& sim, const std::array<ChainBuild, 2>& builds,
                       ChainBuild widest) {
    const DenormalGuard no_denormals;
    std::vector<double> sound(kMostTicks);
    // As many ticks a run as take about kTrialSeconds in the widest build.
    const double per_tick = timed_run(sim, sound, kFewestTicks, widest) / kFewestTicks;
    if (!(per_tick < std::numeric_limits<double>::infinity())) return widest;
    const std::size_t ticks =
        std::clamp(static_cast<std::size_t>(kTrialSeconds / std::max(per_tick, 1e-9)), kFewestTicks,
                   kMostTicks);
    std::array<double, 2> fastest{std::numeric_limits<double>::infinity(),
                                  std::numeric_limits<double>::infinity()};
    for (int round = 0; round < kRounds; ++round)
        for (std::size_t b = 0; b < builds.size(); ++b)
            fastest[b] = std::min(fastest[b], timed_run(sim, sound, ticks, builds[b]));
    if (!(fastest[0] < std::numeric_limits<double>::infinity())) return widest;
    return fastest[1] < (1.0 - kClearMargin) * fastest[0] ? ChainBuild::Avx2 : widest;
}

}  // namespace

ChainBuild fastest_chain_build(Simulation& sim) {
    const ChainBuild widest = chosen_chain_build();
    // Plain (SSE2) is never the fastest where AVX2 runs: only the two widest compete.
    const std::array<ChainBuild, 2> builds{ChainBuild::Avx512, ChainBuild::Avx2};
    if (!chain_build_runs_here(ChainBuild::Avx512) || !sim.bowed_chain_misfit().empty())
        return widest;
    // The trials run `sim` itself, which then resumes from where they found it: a copy of a
    // 10,000-element model would cost more than the trials.
    std::vector<double> state(sim.state_size());
    sim.save_state(state.data());
    const ChainBuild fastest = time_builds(sim, builds, widest);
    sim.load_state(state.data());
    return fastest;
}

}  // namespace archet
