// `archet bench`: the cost of a simulation step in ns per simulated sample, and the real-time
// load it means at the model's rate. Wall-clock timing belongs here, never in the tests.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "archet/builders/bowed_chain.hpp"
#include "archet/common/denormal_guard.hpp"
#include "archet/common/input_error.hpp"
#include "archet/ipc/segment_layout.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/blow_up.hpp"
#include "archet/physics/chain_build_choice.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/simulation.hpp"
#include "commands.hpp"
#include "model_loading.hpp"
#include "option_checks.hpp"

namespace archet::cli {

namespace {

struct BenchArguments {
    std::string model;
    int chain = 0;
    double seconds = 2.0;
    bool json = false;
    bool probes = false;                  ///< read every probe after each step, as the engine does
    std::string chain_build = "fastest";  ///< or a build's name (chain_build_name())
};

// The build of the bowed chain's loop `name` asks for, or none for "fastest" (timed on the model
// once the bow plays).
std::optional<ChainBuild> asked_chain_build(const std::string& name) {
    if (name == "fastest") return std::nullopt;
    for (ChainBuild b : {ChainBuild::Plain, ChainBuild::Avx2, ChainBuild::Avx512}) {
        if (name != chain_build_name(b)) continue;
        if (!chain_build_runs_here(b))
            throw InputError("--chain-build", name + " does not run on this CPU (it runs up to " +
                                                  chain_build_name(chosen_chain_build()) + ")");
        return b;
    }
    throw InputError("--chain-build", "is fastest, avx512, avx2 or plain, not " + name);
}

// With --probes, what the engine's real-time thread reads after each step for the scopes:
// every probe, the stored energy (a sum over the whole model) at every
// ipc::kEnergyProbeEvery-th step, in runs as the engine makes them (Simulation::run() up to
// the next tick that reads the energy). Returns a sum of what it read, for the sink.
double run_reading_probes(Simulation& sim, std::span<double> block, double* rows) {
    const std::size_t probe_count = sim.probe_count();
    bool has_energy_probe = false;
    for (const CompiledProbe& p : sim.model().probes)
        has_energy_probe |= p.kind == ProbeKind::Energy;
    double sum = 0;
    for (std::size_t done = 0; done < block.size();) {
        std::uint64_t length = block.size() - done;
        if (has_energy_probe)
            length = std::min(length, ipc::kEnergyProbeEvery - sim.tick() % ipc::kEnergyProbeEvery);
        const std::span<double> sound = block.subspan(done, length);
        if (sim.run(sound, {.values = rows + done * probe_count, .energy = false}) < length ||
            !std::isfinite(sound.back()))
            throw_blow_up(sim);
        if (has_energy_probe && sim.tick() % ipc::kEnergyProbeEvery == 0)
            sum += sim.stored_energy();
        done += length;
    }
    return sum + block.back() + rows[block.size() * probe_count - 1];
}

int run_bench(const BenchArguments& a) {
    if (a.model.empty() == (a.chain == 0))
        throw InputError("bench", "give either a MODEL file or --chain N");
    if (!(a.seconds > 0 && a.seconds <= 600)) throw InputError("--seconds", "must be in (0, 600]");
    const std::optional<ChainBuild> asked_build = asked_chain_build(a.chain_build);
    Model model;
    if (a.chain > 0) {
        model = build_bowed_chain(a.chain);
        validate_model(model);
    } else {
        model = load_validated_model(a.model, {});
    }
    Simulation sim(compile(model));
    // Measure playing, not a string left to decay: bow back and forth for as long as the
    // bench could possibly last (at 2 ns per step), in 2 s strokes at 0.1 m/s.
    const double longest = a.seconds / 2e-9 / sim.sample_rate() + 1.0;
    std::vector<GestureKeyframe> strokes{{0.0, 0.0, 0.0}, {0.03, 0.0, 0.0015}};
    for (double t = 0.13, x = 0.0, direction = 1; t < longest + 2; t += 2.0, direction = -direction)
        strokes.push_back({t, x += direction * 0.2, 0.0015});
    const Gesture sawing("sawing", strokes);
    sim.set_gesture_track(&sawing);
    const DenormalGuard no_denormals;
    // Warm up past the bow's landing so the friction runs in its steady state.
    const auto warm = static_cast<std::uint64_t>(0.2 * sim.sample_rate());
    double sink = 0;
    const std::size_t probe_count = a.probes ? sim.probe_count() : 0;
    constexpr std::uint64_t batch = 4800;
    std::vector<double> block(batch), rows(batch * probe_count);
    // A model that blows up is not measured: its error names the element (exit status 2).
    auto run_batch = [&] {
        if (probe_count > 0) {
            sink += run_reading_probes(sim, block, rows.data());
            return;
        }
        // The batch at a time, as `archet render` runs it.
        if (sim.run(block) < batch || !std::isfinite(block.back())) throw_blow_up(sim);
        // One sample a batch: summing all of them, one addition waiting for the other, added
        // about 1 ns a sample (a fiftieth of the paper's string) to what is measured.
        sink += block.back();
    };
    for (std::uint64_t done = 0; done < warm; done += batch) run_batch();
    // Chosen once the bow plays (the engine and `play` choose for a model as it is loaded).
    sim.set_chain_build(asked_build ? *asked_build : fastest_chain_build(sim));
    // Several rounds, reporting the median (and the best): one long window on a shared
    // machine measures its neighbours as much as the model.
    using clock = std::chrono::steady_clock;
    constexpr int kRounds = 7;
    std::vector<double> round_ns;
    std::uint64_t steps = 0;
    for (int round = 0; round < kRounds; ++round) {
        const auto start = clock::now();
        std::uint64_t round_steps = 0;
        double elapsed = 0;
        do {
            run_batch();
            round_steps += batch;
            elapsed = std::chrono::duration<double>(clock::now() - start).count();
        } while (elapsed < a.seconds / kRounds);
        round_ns.push_back(elapsed * 1e9 / static_cast<double>(round_steps));
        steps += round_steps;
    }
    // Which step ran: a bowed chain's own loop in run(), else the general one.
    const std::string misfit = sim.bowed_chain_misfit();
    const std::string step_kind = misfit.empty() ? "bowed chain" : "general";
    // The general step's chain loop runs the widest build whatever was asked.
    const ChainBuild ran_build = misfit.empty() ? sim.chain_build() : chosen_chain_build();
    std::sort(round_ns.begin(), round_ns.end());
    const double ns = round_ns[kRounds / 2];
    const double best = round_ns.front();
    const double load = ns * sim.sample_rate() * 1e-9;
    // The modal points nothing reads (a string in modal form has one at every mass, to draw
    // its shape) are never stepped: they are not counted in the cost per mass.
    std::size_t derived = 0;
    for (const CompiledLevel& level : sim.model().levels) derived += level.derived_points.size();
    const std::size_t stepped = model.mats.size() - derived;
    if (a.json) {
        std::printf(
            "{\"model\": \"%s\", \"ns_per_sample\": %.3f, \"best_ns_per_sample\": %.3f, "
            "\"realtime_load\": %.6f, \"masses\": %zu, \"derived_points\": %zu, "
            "\"links\": %zu, \"sample_rate\": %.0f, \"steps\": %llu, \"chain_build\": \"%s\", "
            "\"step\": \"%s\", \"step_reason\": \"%s\", \"checksum\": %.17g}\n",
            model.name.c_str(), ns, best, load, model.mats.size(), derived, model.lias.size(),
            sim.sample_rate(), static_cast<unsigned long long>(steps), chain_build_name(ran_build),
            step_kind.c_str(), misfit.c_str(), sink);
    } else {
        const std::string unstepped =
            derived > 0 ? " (" + std::to_string(derived) + " of them points the modes draw)" : "";
        std::printf(
            "%s: %zu masses%s, %zu links: %.2f ns per sample (median of %d rounds, best %.2f), "
            "%.2f ns per %smass, real-time load %.2f %% at %.0f Hz (%s chain loop, %s step%s)\n",
            model.name.c_str(), model.mats.size(), unstepped.c_str(), model.lias.size(), ns,
            kRounds, best, ns / static_cast<double>(stepped), derived > 0 ? "stepped " : "",
            100 * load, sim.sample_rate(), chain_build_name(ran_build), step_kind.c_str(),
            a.probes ? ", probes read" : "");
        if (!misfit.empty()) std::printf("  (the general step: %s)\n", misfit.c_str());
    }
    return 0;
}

}  // namespace

void add_bench_command(CLI::App& app, Action& action) {
    auto a = std::make_shared<BenchArguments>();
    auto* cmd = app.add_subcommand("bench", "Measure the cost of a simulation step (one core)");
    cmd->add_option("model", a->model, "Model file (.json)");
    cmd->add_option("--chain", a->chain, "Benchmark a bowed chain of N masses instead of a file");
    cmd->add_option("--seconds", a->seconds, "Wall-clock seconds to measure (s)")
        ->check(finite_range(0, 600, "s", true))
        ->capture_default_str();
    cmd->add_flag("--probes", a->probes,
                  "Also read the model's probes after each step as the engine does for its "
                  "scopes (the stored energy at every 16th step)");
    cmd->add_option("--chain-build", a->chain_build,
                    "The bowed chain loop's build: fastest (AVX-512 and AVX2 timed on the model "
                    "once the bow plays, as the engine, render and play choose it), avx512, avx2 "
                    "or plain")
        ->capture_default_str();
    cmd->add_flag("--json", a->json,
                  "Print one JSON object: ns_per_sample, realtime_load, masses, links");
    cmd->callback([&action, a] { action = [a] { return run_bench(*a); }; });
}

}  // namespace archet::cli
