// `archet compare MODEL --vary PARAM=V1,V2[,...] -o DIR`: one gesture played on variants of a
// model (string damping by default in the studio; any ELEMENT.PARAM, string.damping or
// bow.position here). Writes a WAV and a CSV per value, comparison.json and comparison.png.

#include <QDir>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "archet/analysis/comparison.hpp"
#include "archet/common/input_error.hpp"
#include "archet/common/input_limits.hpp"
#include "archet/common/parallel_for.hpp"
#include "archet/files/model_file.hpp"
#include "archet/interruption.hpp"
#include "archet/model/model_variants.hpp"
#include "archet/probe_csv_writer.hpp"
#include "archet/sound_file_writer.hpp"
#include "archet/ui/compare_figure.hpp"
#include "commands.hpp"
#include "figure_application.hpp"
#include "model_loading.hpp"
#include "option_checks.hpp"

namespace archet::cli {

namespace {

struct CompareArguments {
    std::string model, gesture, vary, output;
    double seconds = 0;
    int jobs = 0;
};

// A label as a file name: no path separators.
std::string file_stem(std::string label) {
    for (char& c : label)
        if (c == '/' || c == '\\' || c == ' ') c = '_';
    return label;
}

void write_figure(const std::filesystem::path& path, const std::vector<ComparisonRun>& runs) {
    const FigureApplication app;
    ui::CompareFigure figure;
    figure.show_runs(runs);
    if (!figure.save(QString::fromStdString(path.string())))
        throw InputError(path.string(), "could not write the figure");
}

// The outermost folder of `dir` that does not exist yet (empty when it exists).
std::filesystem::path first_missing_folder(const std::filesystem::path& dir) {
    std::filesystem::path missing;
    std::error_code ec;
    for (auto p = std::filesystem::absolute(dir, ec); !p.empty() && !std::filesystem::exists(p, ec);
         p = p.parent_path()) {
        missing = p;
        if (p == p.parent_path()) break;
    }
    return missing;
}

// Removes the folders made for `dir`, up to `made` (first_missing_folder()): each still empty.
void remove_folders_made(const std::filesystem::path& dir, const std::filesystem::path& made) {
    if (made.empty()) return;
    std::error_code ec;
    for (auto p = std::filesystem::absolute(dir, ec); !p.empty(); p = p.parent_path()) {
        std::filesystem::remove(p, ec);  // an empty folder only
        if (p == made || p == p.parent_path()) break;
    }
}

// The variants on every core (or --jobs threads); a signal stops those under way.
std::vector<ComparisonRun> render_variants(const Model& model, const Gesture& gesture,
                                           const std::string& parameter,
                                           const std::vector<double>& values, double seconds,
                                           int jobs) {
    std::atomic<bool> stop{false};
    ComparedVariants compared = compare_variants(model, gesture, parameter, values, seconds,
                                                 jobs > 0 ? jobs : hardware_jobs(), &stop,
                                                 [&stop](std::size_t, std::size_t) {
                                                     if (interruption_signal() != 0) stop = true;
                                                 });
    if (compared.error) std::rethrow_exception(compared.error);
    throw_if_interrupted("no variant was written");
    return std::move(compared.runs);
}

int run_compare(const CompareArguments& a) {
    const InterruptionGuard stop_on_signal;  // SIGINT, SIGTERM, SIGHUP: stop, keep what is whole
    const auto [parameter, values] = parse_variation(a.vary);
    const Model model = load_validated_model(a.model, {});
    Gesture gesture;
    if (!a.gesture.empty())
        gesture = load_gesture_file(a.gesture);
    else if (model.gesture)
        gesture = *model.gesture;
    else
        throw InputError("--gesture", "the model has no gesture of its own; give one");
    if (a.seconds < 0 || !std::isfinite(a.seconds))
        throw InputError("--seconds", "must be positive seconds");
    const double seconds = a.seconds > 0 ? a.seconds : gesture.duration();
    if (seconds <= 0) throw InputError("--seconds", "the gesture is empty; give --seconds");

    // Every variant is checked before anything is written.
    for (double v : values) {
        Model variant = model;
        set_variant_parameter(variant, parameter, v);
    }
    const std::filesystem::path dir = a.output;
    const std::filesystem::path made_dir = first_missing_folder(dir);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw InputError(a.output, "cannot create the folder: " + ec.message());

    // All rendered before any is written: a variant that fails leaves no file of the others,
    // nor the folders made for them.
    std::vector<ComparisonRun> runs;
    try {
        runs = render_variants(model, gesture, parameter, values, seconds, a.jobs);
    } catch (...) {
        remove_folders_made(dir, made_dir);
        throw;
    }
    nlohmann::ordered_json summary = {{"model", model.name},
                                      {"parameter", parameter},
                                      {"seconds", seconds},
                                      {"runs", nlohmann::ordered_json::array()}};
    std::cout << std::left << std::setw(32) << "variant" << std::setw(12) << "f1 Hz"
              << "dissipated per period (µJ)\n";
    for (const ComparisonRun& run : runs) {
        throw_if_interrupted("the variants before were written, comparison.json was not");
        const std::string stem = file_stem(run.label);
        SoundFileWriter wav(dir / (stem + ".wav"), SoundFormat::Wav,
                            static_cast<int>(std::lround(run.sample_rate)));
        wav.write(run.audio.data(), run.audio.size());
        wav.close();
        ProbeCsvWriter csv(dir / (stem + ".csv"), {"bow_force", "displacement"});
        for (std::size_t i = 0; i < run.audio.size(); ++i) {
            const double row[2] = {run.bow_force[i], run.displacement[i]};
            csv.write_row(static_cast<double>(i + 1) / run.sample_rate, row);
        }
        csv.close();
        std::cout << std::setw(32) << run.label << std::setw(12) << std::fixed
                  << std::setprecision(3) << run.fundamental << std::setprecision(4)
                  << 1e6 * run.dissipated_per_period << std::defaultfloat << "\n";
        summary["runs"].push_back({{"label", run.label},
                                   {"value", run.value},
                                   {"fundamental_hz", run.fundamental},
                                   {"dissipated_per_period_j", run.dissipated_per_period},
                                   {"wav", stem + ".wav"},
                                   {"csv", stem + ".csv"}});
    }
    write_file_atomically(dir / "comparison.json", summary.dump(2) + "\n");
    write_figure(dir / "comparison.png", runs);
    std::cout << "wrote " << runs.size() << " variants, comparison.json and comparison.png to "
              << dir.string() << "\n";
    return 0;
}

}  // namespace

void add_compare_command(CLI::App& app, Action& action) {
    auto a = std::make_shared<CompareArguments>();
    auto* cmd = app.add_subcommand(
        "compare", "Play one gesture on variants of a model and compare them (the paper's Fig. 5)");
    cmd->add_option("model", a->model, "Model file (.json)")->required();
    cmd->add_option("--vary", a->vary,
                    "PARAM=V1,V2[,...]: ELEMENT.PARAM, string.damping (N·s/m per string link) or "
                    "bow.position (β)")
        ->required();
    cmd->add_option("-o,--output", a->output, "Folder for the WAVs, CSVs, JSON and figure")
        ->required();
    cmd->add_option("--gesture", a->gesture, "Gesture file (default: the model's own gesture)");
    cmd->add_option("--seconds", a->seconds, "Seconds to render (default: the gesture's length)")
        ->check(duration_range(limits::kDurationSeconds));
    cmd->add_option("--jobs", a->jobs, "Threads, one variant each (0: every core)")
        ->capture_default_str()
        ->check(CLI::Range(0, 1024));
    cmd->callback([&action, a] { action = [a] { return run_compare(*a); }; });
}

}  // namespace archet::cli
