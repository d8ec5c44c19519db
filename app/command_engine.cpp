// `archet engine --shm NAME`: the real-time core process the studio starts.

#include <memory>

#include "archet/realtime_engine.hpp"
#include "audio_options.hpp"
#include "commands.hpp"

namespace archet::cli {

void add_engine_command(CLI::App& app, Action& action) {
    auto o = std::make_shared<EngineOptions>();
    auto* cmd =
        app.add_subcommand("engine", "Run the real-time core process on a studio's shared memory");
    cmd->add_option("--shm", o->segment,
                    "Shared-memory segment created by the studio (/archet-...)")
        ->required();
    add_audio_options(*cmd, o->audio);
    cmd->add_option("--haptic", o->haptic,
                    "Haptic device: none, sim (the pad moves a simulated hand), evdev:PATH (a "
                    "force-feedback joystick) or sdl:INDEX (an SDL joystick)")
        ->capture_default_str();
    cmd->add_option("--shape-every", o->shape_every, "Blocks between string-shape frames")
        ->capture_default_str();
    cmd->callback([&action, o] { action = [o] { return run_engine(*o); }; });
}

}  // namespace archet::cli
