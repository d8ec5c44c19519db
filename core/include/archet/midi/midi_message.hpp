#pragma once
// One MIDI channel message, decoded from the bytes a port delivers (RtMidi hands over whole
// messages, running status already expanded). Only what a bowed string plays from is kept:
// notes, controllers, pitch bend and channel pressure; system messages (clock, sysex, active
// sensing) and the rest decode to nothing.

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace archet::midi {

struct MidiMessage {
    enum class Kind { NoteOn, NoteOff, Control, PitchBend, ChannelPressure };
    Kind kind = Kind::NoteOn;
    int channel = 1;  ///< 1 … 16
    int number = 0;   ///< the note or the controller, 0 … 127
    int value = 0;    ///< velocity, controller value or pressure 0 … 127; bend −8192 … 8191
};

/// The message, or nothing for the kinds above that are not kept and for malformed bytes
/// (a missing data byte, a data byte with its top bit set). A note-on of velocity 0 is a
/// note-off, as the MIDI specification says.
std::optional<MidiMessage> decode_midi(std::span<const std::uint8_t> bytes);

/// "note on 60 velocity 100 (channel 1)", for messages and logs.
std::string describe(const MidiMessage& message);

}  // namespace archet::midi
