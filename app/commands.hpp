#pragma once
// The `archet` subcommands. Each registers itself on the CLI and runs when chosen.

#include <CLI/CLI.hpp>
#include <functional>

namespace archet::cli {

/// What the chosen subcommand runs; returns the process exit status.
using Action = std::function<int()>;

void add_new_command(CLI::App& app, Action& action);
void add_render_command(CLI::App& app, Action& action);
void add_check_command(CLI::App& app, Action& action);
void add_bench_command(CLI::App& app, Action& action);
void add_modes_command(CLI::App& app, Action& action);
void add_bowing_command(CLI::App& app, Action& action);
void add_engine_command(CLI::App& app, Action& action);
void add_play_command(CLI::App& app, Action& action);
void add_devices_command(CLI::App& app, Action& action);
void add_compare_command(CLI::App& app, Action& action);
void add_examples_command(CLI::App& app, Action& action);
void add_map_command(CLI::App& app, Action& action);
void add_attack_command(CLI::App& app, Action& action);

}  // namespace archet::cli
