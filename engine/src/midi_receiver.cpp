#include "archet/engine/midi_receiver.hpp"

#include <RtMidi.h>

#include <span>
#include <utility>

#include "archet/common/input_error.hpp"

namespace archet {

namespace {

RtMidi::Api api_named(const std::string& name) {
    if (name == "alsa") return RtMidi::LINUX_ALSA;
    if (name == "jack") return RtMidi::UNIX_JACK;
    throw InputError("--midi-api", "\"" + name + "\" is not one of alsa, jack");
}

std::string listed(const std::vector<std::string>& ports) {
    if (ports.empty()) return "none";
    std::string text;
    for (const auto& p : ports) text += (text.empty() ? "\"" : ", \"") + p + "\"";
    return text;
}

}  // namespace

MidiReceiver::MidiReceiver(const MidiInputOptions& options) {
    const RtMidi::Api api = api_named(options.api);
    const std::string where = "--midi " + options.port;
    try {
        // Its own client name: with JACK audio the engine's audio client is "archet" already.
        in_ = std::make_unique<RtMidiIn>(api, "archet-midi", kQueue);
        // Errors come back here rather than as exceptions once this is set; what they say is
        // kept for the control thread (from RtMidi's thread too, at run time).
        in_->setErrorCallback(
            [](RtMidiError::Type type, const std::string& text, void* self) {
                if (type == RtMidiError::WARNING || type == RtMidiError::DEBUG_WARNING) return;
                auto& receiver = *static_cast<MidiReceiver*>(self);
                const std::lock_guard lock(receiver.problem_mutex_);
                receiver.problem_ = text;
            },
            this);
        if (options.port == "virtual") {
            in_->openVirtualPort("midi_in");
            description_ = options.api + " port archet-midi:midi_in";
        } else {
            const unsigned count = in_->getPortCount();
            std::vector<std::string> names;
            for (unsigned i = 0; i < count; ++i) names.push_back(in_->getPortName(i));
            unsigned chosen = count;
            for (unsigned i = 0; i < count && chosen == count; ++i)
                if (names[i].find(options.port) != std::string::npos) chosen = i;
            if (chosen == count)
                throw InputError(where, "no " + options.api + " MIDI input port named like \"" +
                                            options.port + "\"; the ports: " + listed(names) +
                                            " (or give --midi virtual)");
            in_->openPort(chosen, "midi_in");
            description_ = options.api + " port " + names[chosen];
        }
        // RtMidi said why through the error callback (isPortOpen() is false for a virtual
        // port even when it opened).
        if (const std::string problem = take_problem(); !problem.empty())
            throw InputError(where,
                             "cannot open the " + options.api + " MIDI port: " + problem +
                                 (options.api == "jack" ? " (is a JACK server running?)" : ""));
        // System messages (sysex, clock, active sensing) are not played.
        in_->ignoreTypes(true, true, true);
        in_->setCallback(&MidiReceiver::arrived, this);
    } catch (const RtMidiError& e) {
        throw InputError(where, "cannot open " + options.api + " MIDI (" + e.getMessage() + ")" +
                                    (options.api == "jack" ? "; is a JACK server running?" : ""));
    }
}

MidiReceiver::~MidiReceiver() {
    if (in_) {
        in_->cancelCallback();
        in_->closePort();
        in_.reset();  // before the mutex its error callback takes goes
    }
}

// On RtMidi's thread: decode, push, never wait (a full ring counts the message as dropped).
void MidiReceiver::arrived(double, std::vector<unsigned char>* bytes, void* self) {
    auto& receiver = *static_cast<MidiReceiver*>(self);
    if (const auto m = midi::decode_midi(std::span(bytes->data(), bytes->size())))
        receiver.ring_.ring().try_push(*m);
}

std::vector<midi::MidiMessage> MidiReceiver::take() {
    std::vector<midi::MidiMessage> out;
    midi::MidiMessage m;
    while (ring_.ring().try_pop(m)) out.push_back(m);
    return out;
}

std::string MidiReceiver::take_problem() {
    const std::lock_guard lock(problem_mutex_);
    return std::exchange(problem_, {});
}

}  // namespace archet
