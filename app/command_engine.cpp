// `archet engine --shm NAME`: the real-time core process the studio starts.

#include <memory>

#include "archet/realtime_engine.hpp"
#include "commands.hpp"

namespace archet::cli {

void add_engine_command(CLI::App& app, Action& action) {
    auto o = std::make_shared<EngineOptions>();
    auto* cmd =
        app.add_subcommand("engine", "Run the real-time core process on a studio's shared memory");
    cmd->add_option("--shm", o->segment,
                    "Shared-memory segment created by the studio (/archet-...)")
        ->required();
    cmd->add_option("--audio", o->audio.api, "Audio output: jack, alsa, pulse or null")
        ->capture_default_str();
    cmd->add_option("--device", o->audio.device,
                    "Device index of that API (-1: its default; see archet devices)")
        ->capture_default_str();
    cmd->add_option("--buffer", o->audio.buffer_frames, "Frames per audio block")
        ->capture_default_str();
    cmd->add_option("--rate", o->audio.sample_rate, "Audio rate (Hz); models run at it")
        ->capture_default_str();
    cmd->add_option("--shape-every", o->shape_every, "Blocks between string-shape frames")
        ->capture_default_str();
    cmd->callback([&action, o] { action = [o] { return run_engine(*o); }; });
}

}  // namespace archet::cli
