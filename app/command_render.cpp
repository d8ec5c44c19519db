// `archet render`: offline rendering of a model and gesture to a sound file and probe CSV.

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>

#include "archet/compiled_model.hpp"
#include "archet/input_error.hpp"
#include "archet/model_file.hpp"
#include "archet/probe_csv_writer.hpp"
#include "archet/renderer.hpp"
#include "archet/sound_file_writer.hpp"
#include "commands.hpp"
#include "model_loading.hpp"

namespace archet::cli {

namespace {

struct RenderArguments {
    std::string model, output, gesture, probes, format = "wav";
    double duration = 0, sample_rate = 0;
    std::vector<std::string> set;
};

constexpr double kTail = 0.5;  // s rendered after the gesture ends, for the decay

int run_render(const RenderArguments& a) {
    const SoundFormat format = parse_sound_format(a.format);
    if (a.duration < 0 || !std::isfinite(a.duration))
        throw InputError("--duration", "must be positive seconds");
    if (a.sample_rate < 0) throw InputError("--sample-rate", "must be positive Hz");
    const Model model = load_validated_model(a.model, a.set, a.sample_rate);
    std::optional<Gesture> gesture;
    if (!a.gesture.empty())
        gesture = load_gesture_file(a.gesture);
    else if (model.gesture)
        gesture = model.gesture;

    Simulation sim(compile(model));
    sim.set_gesture_track(gesture ? &*gesture : nullptr);
    const double duration =
        a.duration > 0 ? a.duration : (gesture ? gesture->duration() + kTail : 2.0);
    const auto frames = static_cast<std::uint64_t>(std::llround(duration * sim.sample_rate()));
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
    render(sim, options, [&](const RenderBlock& block) {
        audio.write(block.audio, block.frames);
        for (std::size_t i = 0; csv && i < block.frames; ++i)
            csv->write_row(static_cast<double>(block.first_tick + i + 1) / sim.sample_rate(),
                           block.probes + i * block.probe_count);
        if (show_progress)
            std::fprintf(stderr, "\rrendering %5.1f / %.1f s",
                         static_cast<double>(block.first_tick + block.frames) / sim.sample_rate(),
                         duration);
    });
    if (show_progress) std::fputc('\n', stderr);
    audio.close();
    if (csv) csv->close();
    std::cout << "wrote " << a.output << " (" << duration << " s at " << sim.sample_rate()
              << " Hz, peak " << std::fixed << std::setprecision(1)
              << (audio.peak() > 0 ? 20 * std::log10(audio.peak()) : -INFINITY) << " dBFS)"
              << std::defaultfloat;
    if (csv) std::cout << " and " << a.probes;
    std::cout << "\n";
    if (audio.clipped_samples() > 0)
        std::cerr << "archet: warning: " << audio.clipped_samples()
                  << " samples exceeded full scale (peak " << audio.peak()
                  << ") and were clipped; lower the model's output_gain by at least "
                  << std::ceil(20 * std::log10(audio.peak()) * 10) / 10
                  << " dB (the \"output_gain\" field of the model file)\n";
    return 0;
}

}  // namespace

void add_render_command(CLI::App& app, Action& action) {
    auto a = std::make_shared<RenderArguments>();
    auto* cmd =
        app.add_subcommand("render", "Render a model and a gesture offline to a sound file");
    cmd->add_option("model", a->model, "Model file (.json)")->required();
    cmd->add_option("-o,--output", a->output, "Sound file to write")->required();
    cmd->add_option("--gesture", a->gesture, "Gesture file (default: the model's own gesture)");
    cmd->add_option("--duration", a->duration,
                    "Seconds to render (default: gesture + 0.5 s, or 2 s)");
    cmd->add_option("--probes", a->probes,
                    "Write the model's probes to this CSV, one row per sample");
    cmd->add_option("--format", a->format, "Sound file format: wav or flac (24-bit)")
        ->capture_default_str();
    cmd->add_option("--sample-rate", a->sample_rate, "Master clock (Hz; default: the model's)");
    cmd->add_option("--set", a->set, "Override a parameter: ID.PARAM=VALUE (repeatable)");
    cmd->callback([&action, a] { action = [a] { return run_render(*a); }; });
}

}  // namespace archet::cli
