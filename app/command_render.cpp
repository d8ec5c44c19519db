// `archet render`: offline rendering of a model and gesture to a sound file and probe CSV.

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>

#include "archet/common/input_error.hpp"
#include "archet/common/input_limits.hpp"
#include "archet/common/number_text.hpp"
#include "archet/common/scheme_revision.hpp"
#include "archet/files/model_file.hpp"
#include "archet/files/state_file.hpp"
#include "archet/files/take_file.hpp"
#include "archet/files/take_recovery.hpp"
#include "archet/interruption.hpp"
#include "archet/model/model_variants.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/parameter_smoother.hpp"
#include "archet/physics/renderer.hpp"
#include "archet/physics/scheme_changes.hpp"
#include "archet/probe_csv_writer.hpp"
#include "archet/sound_file_writer.hpp"
#include "commands.hpp"
#include "model_loading.hpp"
#include "option_checks.hpp"

namespace archet::cli {

namespace {

struct RenderArguments {
    std::string model, output, gesture, probes, format = "wav", take;
    double duration = 0, sample_rate = 0, max_duration = limits::kDurationSeconds;
    std::vector<std::string> set;
};

constexpr double kTail = 0.5;  // s rendered after the gesture ends, for the decay

// What to render: a model and gesture from the command line, or a recorded take.
struct RenderPlan {
    Model model;
    std::optional<Gesture> gesture;
    double duration = 0;
    std::uint64_t frames = 0;              ///< 0: from duration
    std::vector<double> state;             ///< empty: from the model's start
    std::vector<ParameterChange> changes;  ///< made while the take played
    int scheme = kSchemeRevision;          ///< the revision the take was played with
};

RenderPlan plan_from_arguments(const RenderArguments& a) {
    if (a.model.empty()) throw InputError("model", "give a model file, or --take DIR");
    if (a.duration < 0 || !std::isfinite(a.duration))
        throw InputError("--duration", "must be positive seconds");
    if (a.sample_rate < 0) throw InputError("--sample-rate", "must be positive Hz");
    RenderPlan plan;
    plan.model = load_validated_model(a.model, a.set, a.sample_rate);
    if (!a.gesture.empty())
        plan.gesture = load_gesture_file(a.gesture);
    else if (plan.model.gesture)
        plan.gesture = plan.model.gesture;
    plan.duration =
        a.duration > 0 ? a.duration : (plan.gesture ? plan.gesture->duration() + kTail : 2.0);
    if (plan.duration > a.max_duration)
        throw InputError(a.duration > 0 ? "--duration" : "--gesture",
                         format_number(plan.duration) + " s is longer than --max-duration " +
                             format_number(a.max_duration) +
                             " s; raise --max-duration to render it (an hour of 48 kHz WAV "
                             "takes about 500 MB)");
    return plan;
}

// A take replays as it was played: its model, gesture, starting state and parameter changes,
// for exactly as many samples as it holds. One its recorder never finished is recovered first.
RenderPlan plan_from_take(const RenderArguments& a) {
    if (!a.model.empty() || !a.gesture.empty() || a.duration > 0 || a.sample_rate > 0 ||
        !a.set.empty())
        throw InputError("--take",
                         "replays the take as it was played; drop the model, "
                         "--gesture, --duration, --sample-rate and --set");
    const std::filesystem::path folder = a.take;
    TakeDescription take = read_take_file(folder / "take.json");
    const auto too_long = [&](const TakeDescription& t) {
        const double seconds = static_cast<double>(t.frames) / t.sample_rate;
        if (seconds > a.max_duration)
            throw InputError((folder / "take.json").string(),
                             "holds " + format_number(seconds) + " s, longer than --max-duration " +
                                 format_number(a.max_duration) +
                                 " s; raise --max-duration to render it");
    };
    too_long(take);
    if (!take.complete) {
        const RecoveredTake recovered = recover_take(folder);
        take = recovered.take;
        std::cerr << "archet: note: " << folder.string() << " was interrupted ("
                  << take.interrupted_by << "); recovered "
                  << static_cast<double>(take.frames) / take.sample_rate << " s (" << take.frames
                  << " samples)";
        if (recovered.header_frames != take.frames)
            std::cerr << ": take.wav's header counted " << recovered.header_frames
                      << " and is repaired";
        std::cerr << "; rendering what was recorded\n";
    } else if (take.interrupted) {
        std::cerr << "archet: note: " << folder.string() << " was interrupted ("
                  << take.interrupted_by << ") after "
                  << static_cast<double>(take.frames) / take.sample_rate
                  << " s; rendering what was recorded\n";
    }
    if (take.dropped_samples > 0 || take.dropped_events > 0)
        std::cerr << "archet: warning: " << folder.string() << " lost " << take.dropped_samples
                  << " samples and " << take.dropped_events
                  << " gesture positions or parameter changes while it was recorded: take.wav "
                     "misses the samples, the render the events, so the two differ\n";
    too_long(take);
    if (take.frames == 0)
        throw InputError((folder / "take.json").string(),
                         "the take holds no sample (it ended before it began); nothing to render");
    RenderPlan plan;
    plan.model = load_validated_model((folder / "model.json").string(), {}, take.sample_rate);
    const SchemeChange change =
        take.scheme == kSchemeRevision
            ? SchemeChange::None
            : scheme_change_since(compile(plan.model, take.sample_rate), take.scheme);
    if (change != SchemeChange::None)
        std::cerr << "archet: note: " << folder.string() << " was played with scheme revision "
                  << take.scheme << "; this Archet computes its model with revision "
                  << kSchemeRevision << " (docs/physics.md): "
                  << (change == SchemeChange::Fix
                          ? "a finger's or a bow's push now moves the modal points reading its "
                            "mass before anything reads them (a fix the take's revision lacked), "
                            "so the re-render may differ from take.wav\n"
                          : "the same physics, but the re-render may differ from take.wav by "
                            "rounding, which a bowed string can carry on\n");
    plan.scheme = take.scheme;
    plan.gesture = load_gesture_file(folder / "gesture.json");
    plan.frames = take.frames;
    plan.duration = static_cast<double>(take.frames) / take.sample_rate;
    if (take.has_state) plan.state = read_state_file(folder / "state.bin");
    if (take.has_parameters) plan.changes = read_parameter_changes(folder / "parameters.json");
    return plan;
}

// What was written, and by how much it clipped.
void report_render(const RenderArguments& a, const SoundFileWriter& audio, double duration,
                   double sample_rate, bool with_probes) {
    std::cout << "wrote " << a.output << " (" << duration << " s at " << sample_rate << " Hz, peak "
              << std::fixed << std::setprecision(1)
              << (audio.peak() > 0 ? 20 * std::log10(audio.peak()) : -INFINITY) << " dBFS)"
              << std::defaultfloat;
    if (with_probes) std::cout << " and " << a.probes;
    std::cout << "\n";
    if (audio.clipped_samples() > 0)
        std::cerr << "archet: warning: " << audio.clipped_samples()
                  << " samples exceeded full scale (peak " << audio.peak()
                  << ") and were clipped; lower the model's output_gain by at least "
                  << std::ceil(20 * std::log10(audio.peak()) * 10) / 10
                  << " dB (the \"output_gain\" field of the model file)\n";
}

constexpr const char* kBowPosition = "bow.position";

// The take's bow moved along the string at this tick (MIDI's CC 4): the model with its bow on
// the mass nearest β takes over the whole state, as the engine's real-time thread did.
void move_bow(Simulation& s, const Model& model, double beta, const Gesture* track) {
    Model moved = model;
    set_variant_parameter(moved, "bow.position", beta);
    Simulation next(compile(moved));
    next.set_gesture_track(track);
    std::vector<double> scratch(next.state_size());
    if (!next.continue_from(s, scratch))
        throw InputError("bow.position", "the moved bow's model does not match the take's");
    s = std::move(next);
}

int run_render(const RenderArguments& a) {
    const InterruptionGuard
        stop_on_signal;  // SIGINT, SIGTERM, SIGHUP: stop, leave no temporary file
    const SoundFormat format = parse_sound_format(a.format);
    RenderPlan plan = a.take.empty() ? plan_from_arguments(a) : plan_from_take(a);
    const Model& model = plan.model;
    const std::optional<Gesture>& gesture = plan.gesture;
    const double duration = plan.duration;

    Simulation sim(compile(model));
    sim.compute_as_of(plan.scheme);
    sim.set_gesture_track(gesture ? &*gesture : nullptr);
    if (!plan.state.empty()) {  // after the track: setting it moves the gesture points
        if (plan.state.size() != sim.state_size())
            throw InputError(a.take + "/state.bin", "holds " + std::to_string(plan.state.size()) +
                                                        " numbers but model.json needs " +
                                                        std::to_string(sim.state_size()) +
                                                        "; the files come from different takes");
        sim.load_state(plan.state.data());
    }
    // The take's parameter changes glide in as the engine glided them; "bow.position" (MIDI's
    // CC 4) moves the bow as the engine moved it.
    std::vector<ParameterSlot> slots;
    for (const auto& c : plan.changes)
        slots.push_back(c.parameter == kBowPosition
                            ? ParameterSlot{}
                            : sim.model().resolve_parameter(
                                  ParameterName::parse(c.parameter, a.take + "/parameters.json")));
    const auto frames =
        plan.frames > 0 ? plan.frames
                        : static_cast<std::uint64_t>(std::llround(duration * sim.sample_rate()));
    if (frames == 0) throw InputError("--duration", "renders no sample; give a longer duration");

    SoundFileWriter audio(a.output, format, static_cast<int>(std::lround(sim.sample_rate())));
    std::unique_ptr<ProbeCsvWriter> csv;
    if (!a.probes.empty()) {
        std::vector<std::string> columns;
        for (const auto& p : sim.model().probes) columns.push_back(p.id);
        csv = std::make_unique<ProbeCsvWriter>(a.probes, columns);
    }
    const bool show_progress = ::isatty(STDERR_FILENO) && duration > 5.0;
    RenderOptions options;
    options.frames = frames;
    options.with_probes = csv != nullptr;
    ParameterSmoother smoother;
    std::size_t next_change = 0;
    if (!plan.changes.empty())
        options.before_step = [&](Simulation& s) {
            while (next_change < plan.changes.size() &&
                   plan.changes[next_change].tick == s.tick()) {
                const ParameterChange& c = plan.changes[next_change];
                const ParameterSlot& slot = slots[next_change++];
                if (c.parameter == kBowPosition)
                    move_bow(s, model, c.value, gesture ? &*gesture : nullptr);
                else if (!c.from)
                    smoother.glide(s, slot, c.value, c.glide_samples);
                else if (!smoother.resume({slot, *c.from, c.value, c.done, c.glide_samples}))
                    throw InputError(a.take + "/parameters.json",
                                     "more glides under way at the start than the engine keeps");
            }
            smoother.advance(s);
        };
    // A take begun mid-performance starts at its tick: its probes keep the engine's times.
    const std::uint64_t start_tick = sim.tick();
    render(sim, options, [&](const RenderBlock& block) {
        // Unwinding removes the temporary files: nothing is left, the output is untouched.
        if (interruption_signal()) {
            if (show_progress) std::fputc('\n', stderr);
            throw_if_interrupted(
                "stopped at " +
                std::to_string(static_cast<double>(block.first_frame) / sim.sample_rate()) +
                " s; nothing written, " + a.output + " is as it was");
        }
        audio.write(block.audio, block.frames);
        for (std::size_t i = 0; csv && i < block.frames; ++i)
            csv->write_row(
                static_cast<double>(start_tick + block.first_frame + i + 1) / sim.sample_rate(),
                block.probes + i * block.probe_count);
        if (show_progress)
            std::fprintf(stderr, "\rrendering %5.1f / %.1f s",
                         static_cast<double>(block.first_frame + block.frames) / sim.sample_rate(),
                         duration);
    });
    if (show_progress) std::fputc('\n', stderr);
    audio.close();
    if (csv) csv->close();
    report_render(a, audio, duration, sim.sample_rate(), csv != nullptr);
    return 0;
}

}  // namespace

void add_render_command(CLI::App& app, Action& action) {
    auto a = std::make_shared<RenderArguments>();
    auto* cmd =
        app.add_subcommand("render", "Render a model and a gesture offline to a sound file");
    cmd->add_option("model", a->model, "Model file (.json)");
    cmd->add_option("-o,--output", a->output, "Sound file to write")->required();
    cmd->add_option("--gesture", a->gesture, "Gesture file (default: the model's own gesture)");
    cmd->add_option("--duration", a->duration,
                    "Seconds to render (default: gesture + 0.5 s, or 2 s)")
        ->check(duration_range(INFINITY));
    cmd->add_option("--max-duration", a->max_duration,
                    "Longest render accepted, in seconds (a bound against runaway renders)")
        ->capture_default_str()
        ->check(finite_range(0, 1e6, "s", true));
    cmd->add_option("--probes", a->probes,
                    "Write the model's probes to this CSV, one row per sample");
    cmd->add_option("--format", a->format, "Sound file format: wav or flac (24-bit)")
        ->capture_default_str();
    cmd->add_option("--sample-rate", a->sample_rate, "Master clock (Hz; default: the model's)")
        ->check(sample_rate_range());
    cmd->add_option("--set", a->set, "Override a parameter: ID.PARAM=VALUE (repeatable)");
    cmd->add_option("--take", a->take,
                    "Re-render a recorded take folder exactly (instead of MODEL and --gesture)");
    cmd->callback([&action, a] { action = [a] { return run_render(*a); }; });
}

}  // namespace archet::cli
