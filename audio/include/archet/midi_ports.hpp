#pragma once
// The MIDI inputs a player can choose from, through RtMidi: the ALSA sequencer's and JACK's
// output ports (the sources an input connects to), for the studio's settings, `archet devices`
// and the engine's messages.

#include <string>
#include <vector>

namespace archet {

/// The MIDI APIs Archet reads: "alsa" (the sequencer) and "jack".
const std::vector<std::string>& midi_apis();

/// The ports `api` offers now, by name; empty when it cannot be reached (no JACK server, no
/// sequencer). Throws InputError for an api not in midi_apis().
std::vector<std::string> list_midi_inputs(const std::string& api);

}  // namespace archet
