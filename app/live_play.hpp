#pragma once
// `archet play MODEL --osc PORT --midi [PORT]`: a model played live from OSC and MIDI without
// the studio. `play` then acts as a studio without windows: it starts the real engine
// (`archet engine`, the same process the studio runs) on the same options, loads the model,
// keeps the engine's heartbeat, says on stderr what it refuses, and records a take with it.

#include <string>

#include "archet/audio_output.hpp"

namespace archet::cli {

struct LivePlayArguments {
    std::string model;
    AudioConfig audio;
    std::string haptic = "none";
    std::string take;     ///< a new folder for the take (empty: none)
    double duration = 0;  ///< s; 0: until interrupted (Ctrl-C)
    int osc_port = 0;
    std::string midi, midi_api = "alsa", midi_map;
};

int run_live_play(const LivePlayArguments& arguments);

}  // namespace archet::cli
