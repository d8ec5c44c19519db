// `archet bench`: the cost of step() in ns per simulated sample, and the real-time load it
// means at the model's rate. Wall-clock timing belongs here, never in the tests.

#include <chrono>
#include <cstdio>
#include <memory>

#include "archet/bowed_chain.hpp"
#include "archet/compiled_model.hpp"
#include "archet/input_error.hpp"
#include "archet/model_validation.hpp"
#include "archet/simulation.hpp"
#include "commands.hpp"
#include "model_loading.hpp"

namespace archet::cli {

namespace {

struct BenchArguments {
    std::string model;
    int chain = 0;
    double seconds = 2.0;
    bool json = false;
};

int run_bench(const BenchArguments& a) {
    if (a.model.empty() == (a.chain == 0))
        throw InputError("bench", "give either a MODEL file or --chain N");
    if (!(a.seconds > 0 && a.seconds <= 600)) throw InputError("--seconds", "must be in (0, 600]");
    Model model;
    if (a.chain > 0) {
        model = build_bowed_chain(a.chain);
        validate_model(model);
    } else {
        model = load_validated_model(a.model, {});
    }
    Simulation sim(compile(model));
    // Warm up past the bow's landing so the friction runs in its steady state.
    const auto warm = static_cast<std::uint64_t>(0.2 * sim.sample_rate());
    double sink = 0;
    for (std::uint64_t i = 0; i < warm; ++i) sim.step(), sink += sim.output();
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    std::uint64_t steps = 0;
    double elapsed = 0;
    const std::uint64_t batch = 4800;
    do {
        for (std::uint64_t i = 0; i < batch; ++i) sim.step(), sink += sim.output();
        steps += batch;
        elapsed = std::chrono::duration<double>(clock::now() - start).count();
    } while (elapsed < a.seconds);
    const double ns = elapsed * 1e9 / static_cast<double>(steps);
    const double load = ns * sim.sample_rate() * 1e-9;
    if (a.json) {
        std::printf(
            "{\"model\": \"%s\", \"ns_per_sample\": %.3f, \"realtime_load\": %.6f, \"masses\": "
            "%zu, "
            "\"links\": %zu, \"sample_rate\": %.0f, \"steps\": %llu, \"checksum\": %.17g}\n",
            model.name.c_str(), ns, load, model.mats.size(), model.lias.size(), sim.sample_rate(),
            static_cast<unsigned long long>(steps), sink);
    } else {
        std::printf(
            "%s: %zu masses, %zu links: %.2f ns per sample, %.2f ns per mass, real-time load %.2f "
            "%% at %.0f Hz\n",
            model.name.c_str(), model.mats.size(), model.lias.size(), ns, ns / model.mats.size(),
            100 * load, sim.sample_rate());
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
        ->capture_default_str();
    cmd->add_flag("--json", a->json,
                  "Print one JSON object: ns_per_sample, realtime_load, masses, links");
    cmd->callback([&action, a] { action = [a] { return run_bench(*a); }; });
}

}  // namespace archet::cli
