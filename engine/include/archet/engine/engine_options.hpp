#pragma once
// What `archet engine` is started with: the studio's segment, the device, the take directory
// and how long the studio may stay silent.

#include <string>

#include "archet/audio_output.hpp"
#include "archet/midi/midi_mapping.hpp"

namespace archet {

struct EngineOptions {
    std::string segment;  ///< shared-memory name, from the studio
    AudioConfig audio;    ///< where the sound goes (null sink by default)
    int shape_every = 8;  ///< blocks between string-shape frames
    std::string haptic =
        "none";  ///< none: the pad sets the device position; sim: it moves a simulated hand
    /// The take directory (absolute): StartTake folders must lie inside it. Empty: no takes.
    std::string takes;
    /// The studio's pid, fixed at start (0: the segment header's, read once at attach; later
    /// writes to the header change nothing).
    int studio_pid = 0;
    double studio_timeout = 2;   ///< s without the studio's heartbeat: fade out, play nothing
    double studio_give_up = 60;  ///< s without it: exit
    /// OSC: the UDP port to listen on (0: none) and the address to bind (loopback: only this
    /// machine's programs; 0.0.0.0: the network's too).
    int osc_port = 0;
    std::string osc_host = "127.0.0.1";
    /// OSC out: "HOST:PORT" to send the bow force and the string's energy to, 20 times a
    /// second (empty: none).
    std::string osc_send;
    /// MIDI in: "" (none), "virtual" (a port archet-midi:midi_in others connect to) or a part of
    /// an existing input port's name; through the ALSA sequencer or JACK; played by this map.
    std::string midi;
    std::string midi_api = "alsa";
    midi::MidiMapping midi_mapping = midi::default_midi_mapping();
    /// mlockall the process (the engine's own); off when a test runs the engine in-process.
    bool lock_memory = true;
};

}  // namespace archet
