// What comes from MIDI devices and the player's files: a mapping file (JSON) is read or refused
// with an InputError, and what it accepts holds its bounds; the rest of the input, as MIDI bytes
// in messages of 1 to 3 bytes, decodes or not, and plays through the performer the map makes
// without crashing or making its bow non-finite.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "archet/common/input_error.hpp"
#include "archet/midi/midi_mapping.hpp"
#include "archet/midi/midi_performer.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace archet::midi;
    // The first byte says how much of the input is the map's text.
    const std::size_t text = size == 0 ? 0 : std::min<std::size_t>(data[0] * 4u, size - 1);
    MidiMapping mapping = default_midi_mapping();
    try {
        mapping =
            parse_midi_mapping(std::string(reinterpret_cast<const char*>(data + 1), text), "fuzz");
    } catch (const archet::InputError&) {
    }
    if (mapping.channel < 0 || mapping.channel > 16 || !(mapping.bow_speed > 0) ||
        !std::isfinite(mapping.bend_range))
        __builtin_trap();
    MidiPerformer performer(mapping, {"finger", 220.0, 100.0});
    for (std::size_t at = 1 + text; at < size;) {
        const std::size_t length = std::min<std::size_t>(1 + data[at] % 3, size - at);
        if (const auto m = decode_midi(std::span(data + at, length))) performer.receive(*m);
        at += length;
        const auto round = performer.advance(0.002);
        if (!std::isfinite(round.slide_speed) || !std::isfinite(round.press)) __builtin_trap();
        for (const auto& r : round.parameters())
            if (!std::isfinite(r.value)) __builtin_trap();
    }
    return 0;
}
