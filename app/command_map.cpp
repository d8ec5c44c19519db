// `archet map MODEL --force MIN:MAX:STEPS --position MIN:MAX:STEPS -o MAP.csv`: the model's
// playability map (a Schelleng diagram), on all cores, optionally one shard of it;
// `archet map merge PARTS... -o MAP.csv` joins shards.

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>

#include "archet/analysis/playability.hpp"
#include "archet/common/grid_sweep.hpp"
#include "archet/common/input_error.hpp"
#include "archet/common/input_limits.hpp"
#include "archet/common/parallel_for.hpp"
#include "archet/files/model_file.hpp"
#include "archet/ui/playability_figure.hpp"
#include "commands.hpp"
#include "figure_application.hpp"
#include "model_loading.hpp"
#include "option_checks.hpp"
#include "sweep_options.hpp"

namespace archet::cli {

namespace {

struct MapArguments : SweepOptions {
    std::string model, force = "0.003:1:8", position = "0.06:0.2:5";
    double speed = 0.1, duration = 1.0;
    std::vector<std::string> parts;
};

void write_png(const std::string& path, const MapGrid& grid, const std::vector<MapPoint>& points,
               const SchellengLines& lines) {
    const FigureApplication app;
    ui::PlayabilityFigure figure;
    figure.show_map(grid, points, lines);
    if (!figure.save(QString::fromStdString(path)))
        throw InputError(path, "could not write the figure");
}

void print_summary(const std::vector<MapPoint>& points) {
    std::map<std::string, int> counts;
    for (const auto& p : points) ++counts[to_string(p.analysis.regime)];
    for (const auto& [regime, n] : counts) std::cout << regime << ": " << n << "\n";
    if (const HelmholtzPitch pitch = helmholtz_pitch(points); pitch.points > 0)
        std::printf("helmholtz pitch: %.1f … %.1f cents against the first mode\n", pitch.flattest,
                    pitch.sharpest);
}

int run_map(const MapArguments& a) {
    if (a.model.empty()) throw InputError("MODEL", "give a model file (or: archet map merge)");
    if (a.output.empty()) throw InputError("--output", "give the map's CSV file");
    // Each range on its own, so that a bad one is named by its option.
    auto range = [](const std::string& option, const std::string& key, const std::string& value) {
        try {
            return MapGrid::parse(key + "=" + value);
        } catch (const InputError&) {
            throw InputError(option, "\"" + value + "\": expected MIN:MAX:STEPS, e.g. 0.01:1:8");
        }
    };
    MapGrid grid = range("--force", "force", a.force);
    const MapGrid positions = range("--position", "position", a.position);
    grid.position_min = positions.position_min, grid.position_max = positions.position_max;
    grid.position_steps = positions.position_steps;
    grid.speed = a.speed, grid.duration = a.duration;
    if (!(grid.force_min > 0 && grid.force_max >= grid.force_min && grid.force_steps >= 1))
        throw InputError("--force", "expected 0 < MIN ≤ MAX and STEPS ≥ 1 (N)");
    if (!(grid.position_min > 0 && grid.position_max < 0.5 &&
          grid.position_max >= grid.position_min && grid.position_steps >= 1))
        throw InputError("--position", "expected 0 < MIN ≤ MAX < 0.5 and STEPS ≥ 1 (β)");
    if (!(grid.speed > 0)) throw InputError("--speed", "must be a positive bow speed (m/s)");
    if (!(grid.duration >= 0.2)) throw InputError("--duration", "must be at least 0.2 s");
    a.check_size(grid.force_steps, grid.position_steps, "--force");
    const auto [shard, shards] = a.shard_of();
    const Model model = load_validated_model(a.model, {});
    const int jobs = a.threads();
    const bool show = ::isatty(STDERR_FILENO);
    const PlayedMap map =
        play_map(model, grid, jobs, shard, shards, [&](std::size_t done, std::size_t total) {
            if (show) std::fprintf(stderr, "\rmap %zu / %zu", done, total);
        });
    if (show) std::fputc('\n', stderr);
    write_file_atomically(a.output, format_map(grid, map.points, map.lines));
    if (!a.png.empty()) write_png(a.png, grid, map.points, map.lines);
    print_summary(map.points);
    std::cout << "wrote " << a.output << " (" << map.points.size() << " of " << grid.size()
              << " points" << (shards > 1 ? ", shard " + a.shard : std::string()) << ")\n";
    return 0;
}

int run_merge(const MapArguments& a) {
    if (a.parts.empty()) throw InputError("PARTS", "give the shards' CSV files");
    if (a.model.empty()) throw InputError("--model", "give the model the map was made of");
    const Model model = load_validated_model(a.model, {});
    std::optional<MapGrid> grid;
    std::vector<MapPoint> points;
    for (const auto& part : a.parts) {
        auto [g, p] = parse_map(read_text_file(part), part);
        if (grid && g.describe() != grid->describe())
            throw InputError(part, "is a shard of another grid (" + g.describe() + ")");
        grid = g;
        points.insert(points.end(), p.begin(), p.end());
    }
    check_shards_cover(points, grid->size(), a.parts.front());
    const SchellengLines lines = schelleng_lines(model);
    write_file_atomically(a.output, format_map(*grid, points, lines));
    if (!a.png.empty()) write_png(a.png, *grid, points, lines);
    print_summary(points);
    std::cout << "wrote " << a.output << " (" << points.size() << " points from " << a.parts.size()
              << " shards)\n";
    return 0;
}

}  // namespace

void add_map_command(CLI::App& app, Action& action) {
    auto a = std::make_shared<MapArguments>();
    auto* cmd = app.add_subcommand(
        "map", "Playability map (Schelleng diagram): bow force against bow position");
    cmd->add_option("model", a->model, "Model file (.json)");
    cmd->add_option("--force", a->force, "Bow force MIN:MAX:STEPS (N, log-spaced)")
        ->capture_default_str();
    cmd->add_option("--position", a->position, "Bow position MIN:MAX:STEPS (β)")
        ->capture_default_str();
    cmd->add_option("--speed", a->speed, "Bow speed (m/s)")->capture_default_str();
    cmd->add_option("--duration", a->duration, "Seconds of steady bowing per point")
        ->capture_default_str()
        ->check(finite_range(0.2, 60, "s"));
    add_sweep_options(*cmd, *a, "force steps × position steps", "The map's CSV file",
                      "Draw the map as a PNG too");
    cmd->callback([&action, a] {
        if (!action) action = [a] { return run_map(*a); };
    });
    auto* merge = cmd->add_subcommand("merge", "Join the shards of one map");
    merge->add_option("parts", a->parts, "The shards' CSV files")->required();
    merge->add_option("--model", a->model, "The model the map was made of (for Schelleng's lines)")
        ->required();
    merge->add_option("-o,--output", a->output, "The merged CSV file")->required();
    merge->add_option("--png", a->png, "Draw the map as a PNG too");
    merge->callback([&action, a] { action = [a] { return run_merge(*a); }; });
}

}  // namespace archet::cli
