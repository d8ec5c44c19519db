#include "archet/midi/midi_message.hpp"

namespace archet::midi {

std::optional<MidiMessage> decode_midi(std::span<const std::uint8_t> bytes) {
    if (bytes.empty() || bytes[0] < 0x80 || bytes[0] >= 0xF0) return std::nullopt;
    const int status = bytes[0] & 0xF0;
    const int channel = (bytes[0] & 0x0F) + 1;
    const std::size_t data = status == 0xC0 || status == 0xD0 ? 1 : 2;
    if (bytes.size() < 1 + data) return std::nullopt;
    for (std::size_t i = 1; i <= data; ++i)
        if (bytes[i] & 0x80) return std::nullopt;
    const int a = bytes[1], b = data == 2 ? bytes[2] : 0;
    using K = MidiMessage::Kind;
    switch (status) {
        case 0x80:
            return MidiMessage{K::NoteOff, channel, a, b};
        case 0x90:
            return MidiMessage{b == 0 ? K::NoteOff : K::NoteOn, channel, a, b};
        case 0xB0:
            return MidiMessage{K::Control, channel, a, b};
        case 0xD0:
            return MidiMessage{K::ChannelPressure, channel, 0, a};
        case 0xE0:
            return MidiMessage{K::PitchBend, channel, 0, (a | (b << 7)) - 8192};
        default:  // polyphonic pressure, program change
            return std::nullopt;
    }
}

std::string describe(const MidiMessage& m) {
    const std::string channel = " (channel " + std::to_string(m.channel) + ")";
    switch (m.kind) {
        case MidiMessage::Kind::NoteOn:
            return "note on " + std::to_string(m.number) + " velocity " + std::to_string(m.value) +
                   channel;
        case MidiMessage::Kind::NoteOff:
            return "note off " + std::to_string(m.number) + channel;
        case MidiMessage::Kind::Control:
            return "CC " + std::to_string(m.number) + " = " + std::to_string(m.value) + channel;
        case MidiMessage::Kind::PitchBend:
            return "pitch bend " + std::to_string(m.value) + channel;
        case MidiMessage::Kind::ChannelPressure:
            break;
    }
    return "channel pressure " + std::to_string(m.value) + channel;
}

}  // namespace archet::midi
