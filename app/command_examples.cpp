// `archet examples -o DIR`: renders the paper's sound examples (see sound_examples.hpp).

#include <iostream>
#include <memory>

#include "archet/interruption.hpp"
#include "archet/sound_examples.hpp"
#include "commands.hpp"
#include "resource_folder.hpp"

namespace archet::cli {

namespace {
struct ExamplesArguments {
    std::string output = "sound-examples";
    std::string resources = resource_folder().string();
};

int run_examples(const ExamplesArguments& a) {
    const InterruptionGuard
        stop_on_signal;  // SIGINT, SIGTERM, SIGHUP: stop, leave no temporary file
    for (const SoundExample& e : sound_examples()) {
        const auto path = render_sound_example(e, a.resources, a.output);
        std::cout << path.string() << "  " << e.what << "\n";
    }
    return 0;
}
}  // namespace

void add_examples_command(CLI::App& app, Action& action) {
    auto a = std::make_shared<ExamplesArguments>();
    auto* cmd = app.add_subcommand("examples", "Render the paper's sound examples to a folder");
    cmd->add_option("-o,--output", a->output, "Folder for the WAV files")->capture_default_str();
    cmd->add_option("--resources", a->resources, "Folder with models/ and gestures/")
        ->capture_default_str();
    cmd->callback([&action, a] { action = [a] { return run_examples(*a); }; });
}

}  // namespace archet::cli
