// `archet attack MODEL --acceleration MIN:MAX:STEPS --force MIN:MAX:STEPS -o ATTACK.csv`: the
// model's attack map (a Guettler diagram) on all cores, optionally one shard of it;
// `archet attack merge PARTS... -o ATTACK.csv` joins shards.

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>

#include "archet/analysis/attack.hpp"
#include "archet/common/grid_sweep.hpp"
#include "archet/common/input_error.hpp"
#include "archet/common/input_limits.hpp"
#include "archet/common/number_text.hpp"
#include "archet/common/parallel_for.hpp"
#include "archet/files/model_file.hpp"
#include "archet/ui/attack_figure.hpp"
#include "commands.hpp"
#include "figure_application.hpp"
#include "model_loading.hpp"
#include "option_checks.hpp"
#include "sweep_options.hpp"

namespace archet::cli {

namespace {

// The default grid, in the options' words.
const AttackGrid kDefaultGrid;
std::string range_text(double lo, double hi, int steps) {
    return format_number(lo) + ":" + format_number(hi) + ":" + std::to_string(steps);
}

struct AttackArguments : SweepOptions {
    std::string model,
        acceleration = range_text(kDefaultGrid.acceleration_min, kDefaultGrid.acceleration_max,
                                  kDefaultGrid.acceleration_steps),
        force =
            range_text(kDefaultGrid.force_min, kDefaultGrid.force_max, kDefaultGrid.force_steps),
        axes = kDefaultGrid.log_axes ? "log" : "linear";
    double position = 0;
    int periods_max = 25;
    std::vector<std::string> parts;
};

void write_png(const std::string& path, const AttackGrid& grid,
               const std::vector<AttackPoint>& points, const std::string& title) {
    const FigureApplication app;
    ui::AttackFigure figure;
    figure.show_attacks(grid, points, QString::fromStdString(title));
    if (!figure.save(QString::fromStdString(path)))
        throw InputError(path, "could not write the figure");
}

void print_summary(const std::vector<AttackPoint>& points) {
    std::map<std::string, int> counts;
    for (const auto& p : points) ++counts[to_string(p.transient.kind)];
    for (const auto& [kind, n] : counts) std::cout << kind << ": " << n << "\n";
}

AttackGrid grid_from(const AttackArguments& a) {
    // Each range on its own, so that a bad one is named by its option.
    auto range = [](const std::string& option, const std::string& key, const std::string& value) {
        try {
            return AttackGrid::parse(key + "=" + value);
        } catch (const InputError&) {
            throw InputError(
                option, "\"" + value + "\": expected MIN:MAX:STEPS, e.g. " + range_text(1, 40, 16));
        }
    };
    AttackGrid grid = range("--acceleration", "acceleration", a.acceleration);
    const AttackGrid forces = range("--force", "force", a.force);
    grid.force_min = forces.force_min, grid.force_max = forces.force_max;
    grid.force_steps = forces.force_steps;
    if (a.axes != "linear" && a.axes != "log")
        throw InputError("--axes", "\"" + a.axes + "\": expected linear or log");
    grid.log_axes = a.axes == "log";
    grid.position = a.position, grid.periods_max = a.periods_max;
    if (!(grid.acceleration_min > 0 && grid.acceleration_max >= grid.acceleration_min &&
          grid.acceleration_max <= 1000 && grid.acceleration_steps >= 1))
        throw InputError("--acceleration", "expected 0 < MIN ≤ MAX ≤ 1000 and STEPS ≥ 1 (m/s²)");
    if (const std::string problem = grid.problem(); !problem.empty())
        throw InputError("--force", "expected " + problem);
    a.check_size(grid.acceleration_steps, grid.force_steps, "--force");
    return grid;
}

int run_attack(const AttackArguments& a) {
    if (a.model.empty()) throw InputError("MODEL", "give a model file (or: archet attack merge)");
    if (a.output.empty()) throw InputError("--output", "give the attack map's CSV file");
    const AttackGrid grid = grid_from(a);
    const auto [shard, shards] = a.shard_of();
    const Model model = load_validated_model(a.model, {});
    const int jobs = a.threads();
    const bool show = ::isatty(STDERR_FILENO);
    const AttackMap map =
        play_attack(model, grid, jobs, shard, shards, [&](std::size_t done, std::size_t total) {
            if (show) std::fprintf(stderr, "\rattack %zu / %zu", done, total);
        });
    if (show) std::fputc('\n', stderr);
    write_file_atomically(a.output, format_attack(map));
    const auto& points = map.points;
    if (!a.png.empty()) write_png(a.png, grid, points, model.name);
    print_summary(points);
    std::cout << "wrote " << a.output << " (" << points.size() << " of " << grid.size() << " points"
              << (shards > 1 ? ", shard " + a.shard : std::string()) << ")\n";
    return 0;
}

int run_merge(const AttackArguments& a) {
    if (a.parts.empty()) throw InputError("PARTS", "give the shards' CSV files");
    std::optional<AttackMap> merged;
    for (const auto& part : a.parts) {
        AttackMap map = parse_attack(read_text_file(part), part);
        if (merged && map.grid.describe() != merged->grid.describe())
            throw InputError(part, "is a shard of another grid (" + map.grid.describe() + ")");
        if (!merged) merged = AttackMap{map.grid, {}, map.pitch};
        merged->points.insert(merged->points.end(), map.points.begin(), map.points.end());
    }
    auto& points = merged->points;
    check_shards_cover(points, merged->grid.size(), a.parts.front());
    write_file_atomically(a.output, format_attack(*merged));
    if (!a.png.empty()) write_png(a.png, merged->grid, points, a.output);
    print_summary(points);
    std::cout << "wrote " << a.output << " (" << points.size() << " points from " << a.parts.size()
              << " shards)\n";
    return 0;
}

}  // namespace

void add_attack_command(CLI::App& app, Action& action) {
    auto a = std::make_shared<AttackArguments>();
    auto* cmd = app.add_subcommand(
        "attack", "Attack map (Guettler diagram): bow acceleration against bow force");
    cmd->add_option("model", a->model, "Model file (.json)");
    cmd->add_option("--acceleration", a->acceleration,
                    "The hand's acceleration MIN:MAX:STEPS (m/s²)")
        ->capture_default_str();
    cmd->add_option("--force", a->force, "Bow force MIN:MAX:STEPS (N)")->capture_default_str();
    cmd->add_option("--axes", a->axes, "Grid spacing and figure axes: linear or log")
        ->capture_default_str();
    cmd->add_option("--position", a->position, "Bow position β (0: the model's own)")
        ->capture_default_str()
        ->check(finite_range(0, 0.5, "β"));
    cmd->add_option("--periods-max", a->periods_max,
                    "Longest transient counted, in periods (longer ones are \"never\")")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    add_sweep_options(*cmd, *a, "acceleration steps × force steps", "The attack map's CSV file",
                      "Draw the diagram as a PNG too");
    cmd->callback([&action, a] {
        if (!action) action = [a] { return run_attack(*a); };
    });
    auto* merge = cmd->add_subcommand("merge", "Join the shards of one attack map");
    merge->add_option("parts", a->parts, "The shards' CSV files")->required();
    merge->add_option("-o,--output", a->output, "The merged CSV file")->required();
    merge->add_option("--png", a->png, "Draw the diagram as a PNG too");
    merge->callback([&action, a] { action = [a] { return run_merge(*a); }; });
}

}  // namespace archet::cli
