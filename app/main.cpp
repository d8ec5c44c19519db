// `archet`: the command line of the Archet studio.

#include <cstdio>
#include <iostream>

#include "archet/common/input_error.hpp"
#include "archet/common/printable_text.hpp"
#include "archet/interruption.hpp"
#include "commands.hpp"

#ifndef ARCHET_VERSION
#define ARCHET_VERSION "0.0.0"
#endif

int main(int argc, char** argv) {
    CLI::App app{"Archet: physically modelled bowed strings (CORDIS-ANIMA mass-interaction)"};
    app.set_version_flag("--version", std::string("archet ") + ARCHET_VERSION);
    app.require_subcommand(1);
    app.get_formatter()->column_width(36);
    archet::cli::Action action;
    archet::cli::add_new_command(app, action);
    archet::cli::add_render_command(app, action);
    archet::cli::add_check_command(app, action);
    archet::cli::add_modes_command(app, action);
    archet::cli::add_bowing_command(app, action);
    archet::cli::add_compare_command(app, action);
    archet::cli::add_examples_command(app, action);
    archet::cli::add_map_command(app, action);
    archet::cli::add_attack_command(app, action);
    archet::cli::add_bench_command(app, action);
    archet::cli::add_engine_command(app, action);
    archet::cli::add_play_command(app, action);
    archet::cli::add_devices_command(app, action);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int status = app.exit(e);
        return status == 0 ? 0 : 2;  // bad command line: invalid input
    }
    try {
        return action();
    } catch (const archet::InputError& e) {
        std::cerr << "archet: " << archet::printable_message(e.what()) << "\n";
        return 2;
    } catch (const archet::Interrupted& e) {  // SIGINT, SIGTERM, SIGHUP: 128 + the signal
        std::cerr << "archet: " << archet::printable_message(e.what()) << "\n";
        return e.status();
    } catch (const std::exception& e) {
        std::cerr << "archet: internal error: " << archet::printable_message(e.what()) << "\n";
        return 1;
    }
}
