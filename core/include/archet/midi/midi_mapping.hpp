#pragma once
// How MIDI plays a model: which channel is heard, how hard a note's velocity bows, how far the
// pitch wheel bends, and what each controller moves. Read from a JSON file (docs/midi.md) or
// the default, which follows STK's Bowed where it has a meaning here:
//
//   CC 2  (breath)          bow force, N        STK: bow pressure
//   CC 4  (foot)            bow position, β     STK: bow position
//   CC 1  (modulation)      vibrato depth, semitones   STK: vibrato gain
//   CC 11 (expression)      vibrato rate, Hz    STK: vibrato frequency
//   128   (channel pressure) bow speed, m/s     STK: volume (its bow velocity)

#include <filesystem>
#include <string>
#include <vector>

#include "archet/model/parameter_name.hpp"

namespace archet::midi {

/// What a controller moves.
enum class MidiTarget {
    BowForce,        ///< N, while a note bows
    BowSpeed,        ///< m/s
    VibratoDepth,    ///< semitones either way
    VibratoRate,     ///< Hz
    FingerPressure,  ///< the model's finger, 0 … 1
    BowPosition,     ///< β, where the bow meets the string (its contact moves to a mass)
    Parameter        ///< any run-time parameter of the model, ELEMENT.PARAM
};

/// The controller number that stands for channel pressure (aftertouch), as in STK.
constexpr int kChannelPressure = 128;

struct ControlRoute {
    int controller = 0;  ///< 0 … 127, or kChannelPressure
    MidiTarget target = MidiTarget::BowForce;
    ParameterName parameter;          ///< Parameter only
    double minimum = 0, maximum = 1;  ///< the values of controller 0 and 127
};

struct MidiMapping {
    int channel = 0;                   ///< 0: every channel; 1 … 16: that one only
    double bend_range = 2;             ///< semitones either way at full bend
    double velocity_force_min = 0.02;  ///< N, velocity 1
    double velocity_force_max = 0.2;   ///< N, velocity 127 (the pad's usual press is 0.15 N)
    double bow_speed = 0.1;            ///< m/s, until a controller sets it
    std::vector<ControlRoute> controls;

    /// The route of `controller`, or null.
    const ControlRoute* route(int controller) const;
};

/// The default map (the table above).
MidiMapping default_midi_mapping();

/// Reads a map; throws InputError naming the file, the entry and what to change.
MidiMapping parse_midi_mapping(const std::string& text, const std::string& source);
MidiMapping load_midi_mapping(const std::filesystem::path& path);
/// The map as the JSON a file holds (parse_midi_mapping reads it back the same).
std::string write_midi_mapping(const MidiMapping& mapping);

/// "bow_force", "bow_speed", "vibrato_depth", "vibrato_rate", "finger_pressure", "parameter".
std::string to_string(MidiTarget target);

}  // namespace archet::midi
