// `archet engine --shm NAME`: the real-time core process the studio starts.

#include <memory>

#include "archet/engine/realtime_engine.hpp"
#include "archet/midi/midi_mapping.hpp"
#include "audio_options.hpp"
#include "commands.hpp"
#include "option_checks.hpp"

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
    cmd->add_option("--takes", o->takes,
                    "Take directory (absolute; created if missing): takes are recorded only in "
                    "folders inside it");
    cmd->add_option("--studio-pid", o->studio_pid,
                    "The studio's process id (default: the segment's owner, read once at start)")
        ->check(CLI::Range(2, 1 << 30));
    cmd->add_option("--studio-timeout", o->studio_timeout,
                    "Seconds without the studio's heartbeat before the engine fades out and "
                    "plays nothing (sound comes back when it beats again)")
        ->check(finite_range(0.05, 3600.0, "s"))
        ->capture_default_str();
    cmd->add_option("--studio-give-up", o->studio_give_up,
                    "Seconds without the studio's heartbeat before the engine exits")
        ->check(finite_range(0.1, 86400.0, "s"))
        ->capture_default_str();
    cmd->add_option("--osc", o->osc_port,
                    "Listen for OSC on this UDP port (/archet/bow/slide, /archet/bow/press, "
                    "/archet/finger, /archet/finger/pressure, /archet/param, /archet/record)")
        ->check(CLI::Range(1, 65535));
    cmd->add_option("--osc-host", o->osc_host,
                    "Address the OSC port listens on (0.0.0.0: every interface)")
        ->capture_default_str();
    cmd->add_option("--osc-send", o->osc_send,
                    "Send /archet/out/bow_force, /archet/out/friction and /archet/out/energy to "
                    "this HOST:PORT, 20 times a second");
    cmd->add_option("--midi", o->midi,
                    "MIDI in: virtual (a port archet-midi:midi_in to connect controllers and "
                    "sequencers to) or a part of an existing input port's name")
        ->expected(0, 1)
        ->default_str("virtual");
    cmd->add_option("--midi-api", o->midi_api,
                    "Where MIDI comes from: alsa (the sequencer) or jack")
        ->check(CLI::IsMember({"alsa", "jack"}))
        ->capture_default_str();
    auto* map = cmd->add_option("--midi-map",
                                "How MIDI plays the model: a mapping file (JSON, "
                                "docs/midi.md; default: STK's Bowed's controllers)");
    cmd->add_option("--shape-every", o->shape_every, "Blocks between string-shape frames")
        ->capture_default_str();
    cmd->callback([&action, o, map] {
        const std::string map_file = map->count() > 0 ? map->as<std::string>() : "";
        action = [o, map_file] {
            // A bad map is refused before anything starts (status 2), naming the entry.
            if (!map_file.empty()) o->midi_mapping = midi::load_midi_mapping(map_file);
            return run_engine(*o);
        };
    });
}

}  // namespace archet::cli
