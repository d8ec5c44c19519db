// Cost of step() on the paper's strings and on large chains, of compiling a large model, of
// building a string, and of its modal analysis.

#include <benchmark/benchmark.h>

#include <functional>
#include <memory>
#include <string>

#include "archet/analysis/modal_analysis.hpp"
#include "archet/builders/bowed_chain.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/common/denormal_guard.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/gesture.hpp"
#include "archet/model/linear_system.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/parameter_name.hpp"
#include "archet/physics/chain_build_choice.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/simulation.hpp"

namespace {

// Steps a model while it plays: one steady stroke at 0.1 m/s, as long as any run can last.
// (A model's own gesture ends within seconds, and a benchmark runs for minutes of model time:
// it would time a bow resting on a string that has died away.) `prepare` may change the
// simulation first.
void run_steps(benchmark::State& state, const archet::Model& model,
               const std::function<void(archet::Simulation&)>& prepare = {}) {
    archet::Simulation sim(archet::compile(model));
    if (prepare) prepare(sim);
    const archet::Gesture stroke = archet::steady_bow_gesture(0.1, 0.0015, 1e5);
    sim.set_gesture_track(&stroke);
    const archet::DenormalGuard no_denormals;
    for (int i = 0; i < 9600; ++i) sim.step();  // past the bow's landing
    for (auto _ : state) {
        sim.step();
        benchmark::DoNotOptimize(sim.output());
    }
    state.counters["ns_per_mass"] = benchmark::Counter(
        static_cast<double>(state.iterations()) * static_cast<double>(model.mats.size()),
        benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_BowedString(benchmark::State& state) {
    archet::BowedStringOptions o;
    o.pitch = static_cast<double>(state.range(0));
    run_steps(state, archet::build_bowed_string(o));
}
BENCHMARK(BM_BowedString)->Arg(110)->Arg(220)->Arg(440)->Arg(880);

// The paper's chaplet of 30 or 60 masses at 220 Hz in modal form (--structure modal): an
// oscillator per mode, and three modal points (the ends, the bowing point) of a term per mode,
// whose sums the step makes after each force on the string.
void BM_ModalString(benchmark::State& state) {
    archet::BowedStringOptions o;
    o.pitch = 220;
    o.paper = true;
    o.masses = static_cast<int>(state.range(0));
    o.structure = archet::Structure::Modal;
    run_steps(state, archet::build_bowed_string(o));
}
BENCHMARK(BM_ModalString)->Arg(30)->Arg(60);

// The chain loop alone, in each build: on a 60-mass string (with its losses to rest, as
// shipped) and on long bare chains (archet bench --chain), to split a step's cost between
// the loop and the rest.
void time_chain_loop(benchmark::State& state, archet::CompiledModel compiled) {
    const auto build = static_cast<archet::ChainBuild>(state.range(0));
    if (!archet::chain_build_runs_here(build)) return state.SkipWithError("not on this CPU");
    archet::CompiledLevel& audio = compiled.levels.front();
    std::vector<double> xn(audio.buffer[0].size());
    for (auto _ : state) {
        archet::integrate_chain(audio, xn.data(), build);
        benchmark::DoNotOptimize(xn.data());
    }
    state.SetLabel(archet::chain_build_name(build));
}

void BM_ChainLoop(benchmark::State& state) {
    archet::BowedStringOptions o;
    o.masses = static_cast<int>(state.range(1));
    o.body = "none";
    time_chain_loop(state, archet::compile(archet::build_bowed_string(o)));
}
BENCHMARK(BM_ChainLoop)->ArgsProduct({{0, 1, 2}, {30, 60}});

void BM_LongChainLoop(benchmark::State& state) {
    time_chain_loop(state,
                    archet::compile(archet::build_bowed_chain(static_cast<int>(state.range(1)))));
}
BENCHMARK(BM_LongChainLoop)->ArgsProduct({{1, 2}, {1024, 10000}});

// The stored energy the engine's energy probe reads: O(N), like a step.
void BM_StoredEnergy(benchmark::State& state) {
    archet::BowedStringOptions o;
    o.pitch = static_cast<double>(state.range(0));
    archet::Simulation sim(archet::compile(archet::build_bowed_string(o)));
    for (int i = 0; i < 9600; ++i) sim.step();
    for (auto _ : state) benchmark::DoNotOptimize(sim.stored_energy());
}
BENCHMARK(BM_StoredEnergy)->Arg(110)->Arg(220);

void BM_BowedChain(benchmark::State& state) {
    run_steps(state, archet::build_bowed_chain(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_BowedChain)->Arg(60)->Arg(1000)->Arg(10000)->Arg(65536);

// A long chain after one of its links was changed while it played (a damper touched up in the
// studio's inspector): the chain loop still broadcasts what the MATs on either side share.
void BM_BowedChainAfterOneEdit(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    run_steps(state, archet::build_bowed_chain(n), [n](archet::Simulation& sim) {
        const archet::ParameterSlot damping = sim.model().resolve_parameter(
            archet::ParameterName{"l" + std::to_string(n / 2), "damping"});
        sim.write_slot(damping, 2.0 * sim.read_slot(damping));
    });
}
BENCHMARK(BM_BowedChainAfterOneEdit)->Arg(10000)->Arg(65536);

void BM_Compile(benchmark::State& state) {
    const archet::Model model = archet::build_bowed_chain(static_cast<int>(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(archet::compile(model));
}
BENCHMARK(BM_Compile)->Arg(5000)->Arg(10000)->Unit(benchmark::kMillisecond);

void BM_Validate(benchmark::State& state) {
    const archet::Model model = archet::build_bowed_chain(static_cast<int>(state.range(0)));
    for (auto _ : state) archet::validate_model(model);
}
BENCHMARK(BM_Validate)->Arg(5000)->Arg(10000)->Unit(benchmark::kMillisecond);

// What the engine's control thread does to swap a model in (control_thread.cpp, nrt_load), up
// to the pointer it hands the real-time thread: parse the file, validate, compile, and build
// the Simulation from a copy (the engine keeps the compiled model to resolve parameters), and
// time the chain loop's builds on it to choose the fastest. Its cost check steps
// another copy for at most 20 ms; the hand-over itself is one atomic exchange, taken at the
// next block boundary.
void BM_ModelSwap(benchmark::State& state) {
    const std::string text =
        archet::format_model(archet::build_bowed_chain(static_cast<int>(state.range(0))));
    for (auto _ : state) {
        archet::Model model = archet::parse_model(text);
        archet::validate_model(model);
        const archet::CompiledModel compiled = archet::compile(model);
        auto running = std::make_unique<archet::Simulation>(compiled);
        running->set_chain_build(archet::fastest_chain_build(*running));
        benchmark::DoNotOptimize(running.get());
    }
}
BENCHMARK(BM_ModelSwap)->Arg(5000)->Arg(10000)->Unit(benchmark::kMillisecond);

// The part of the swap after validation: compile, and the Simulation built from a copy.
void BM_CompileAndPrepare(benchmark::State& state) {
    const archet::Model model = archet::build_bowed_chain(static_cast<int>(state.range(0)));
    for (auto _ : state) {
        const archet::CompiledModel compiled = archet::compile(model);
        auto running = std::make_unique<archet::Simulation>(compiled);
        benchmark::DoNotOptimize(running.get());
    }
}
BENCHMARK(BM_CompileAndPrepare)->Arg(5000)->Arg(10000)->Unit(benchmark::kMillisecond);

void BM_ParseModel(benchmark::State& state) {
    const std::string text =
        archet::format_model(archet::build_bowed_chain(static_cast<int>(state.range(0))));
    for (auto _ : state) benchmark::DoNotOptimize(archet::parse_model(text));
}
BENCHMARK(BM_ParseModel)->Arg(5000)->Arg(10000)->Unit(benchmark::kMillisecond);

// `archet new bowed-string --pitch P`: the count search, tuning, losses and the stroke's
// Helmholtz band, at a violin's G (196 Hz), a cello's C (65 Hz) and a double bass's E (41 Hz).
void BM_NewString(benchmark::State& state) {
    archet::BowedStringOptions o;
    o.pitch = static_cast<double>(state.range(0));
    for (auto _ : state) benchmark::DoNotOptimize(archet::build_bowed_string(o));
}
BENCHMARK(BM_NewString)->Arg(196)->Arg(65)->Arg(41)->Unit(benchmark::kMillisecond);

// `archet new bowed-string --tuning harmonic --pitch P`, a cello's string at 65 Hz (its C, 323
// masses) and 131 Hz (its G): the harmonic tuning reads every partial of the damped string at
// each of its corrections.
void BM_NewHarmonicString(benchmark::State& state) {
    archet::BowedStringOptions o;
    o.pitch = static_cast<double>(state.range(0)), o.tuning = archet::Tuning::Harmonic;
    o.tension = 130, o.linear_density = 0.0148;
    for (auto _ : state) benchmark::DoNotOptimize(archet::build_bowed_string(o));
}
BENCHMARK(BM_NewHarmonicString)->Arg(131)->Arg(65)->Unit(benchmark::kMillisecond);

// The Modes tab's and `archet modes`' analysis of a full-bandwidth string at P Hz (with its
// body): each mode's shape from its root, against the dense solve's eigenvectors (its reference).
archet::LinearSystem string_system(double pitch, archet::Model& model) {
    archet::BowedStringOptions o;
    o.pitch = pitch;
    model = archet::build_bowed_string(o);
    return archet::sounding_part(model);
}
void BM_AnalyseModes(benchmark::State& state) {
    archet::Model model;
    const archet::LinearSystem sys = string_system(static_cast<double>(state.range(0)), model);
    for (auto _ : state) benchmark::DoNotOptimize(archet::analyse_modes(sys, model));
}
BENCHMARK(BM_AnalyseModes)->Arg(110)->Arg(41)->Unit(benchmark::kMillisecond);
void BM_AnalyseModesWithEigenvectors(benchmark::State& state) {
    archet::Model model;
    const archet::LinearSystem sys = string_system(static_cast<double>(state.range(0)), model);
    for (auto _ : state)
        benchmark::DoNotOptimize(
            archet::class_modes(archet::solve_modes_with_eigenvectors(sys), sys, model));
}
BENCHMARK(BM_AnalyseModesWithEigenvectors)->Arg(110)->Arg(41)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
