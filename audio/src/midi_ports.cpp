#include "archet/midi_ports.hpp"

#include <RtMidi.h>

#include "archet/common/input_error.hpp"

namespace archet {

const std::vector<std::string>& midi_apis() {
    static const std::vector<std::string> apis{"alsa", "jack"};
    return apis;
}

std::vector<std::string> list_midi_inputs(const std::string& api) {
    RtMidi::Api which = RtMidi::LINUX_ALSA;
    if (api == "jack")
        which = RtMidi::UNIX_JACK;
    else if (api != "alsa")
        throw InputError("--midi-api", "\"" + api + "\" is not one of alsa, jack");
    std::vector<std::string> names;
    try {
        RtMidiIn in(which, "archet-list");
        // Quiet: a missing JACK server or sequencer is an empty list here, not an error.
        in.setErrorCallback([](RtMidiError::Type, const std::string&, void*) {}, nullptr);
        for (unsigned i = 0; i < in.getPortCount(); ++i) names.push_back(in.getPortName(i));
    } catch (const RtMidiError&) {
    }
    return names;
}

}  // namespace archet
