#pragma once
// What a take folder holds besides its audio (take.wav), probes (probes.csv) and gesture
// (gesture.json): take.json, which says how to re-render it; model.json, the model as it was
// played; state.bin, the model's state where the take began (absent when it began at the
// model's start); and parameters.json, the parameter changes made while it was recorded.
// `archet render --take DIR` reads them all and reproduces take.wav to the byte.
//
// take.json is written when the take starts (`"complete": false`) and again when it ends. A
// take stopped by a signal is finished and says so (`"interrupted": true`, `"interrupted_by"`);
// one whose recorder never finished it (killed, crashed) is recovered by take_recovery.hpp.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "archet/common/scheme_revision.hpp"

namespace archet {

struct TakeDescription {
    double sample_rate = 48000;
    std::uint64_t frames = 0;      ///< samples in take.wav
    std::uint64_t start_tick = 0;  ///< master tick of the take's first sample
    bool has_state = false;        ///< state.bin: the take began mid-performance
    bool has_parameters = false;   ///< parameters.json: parameters changed during the take
    bool complete = true;          ///< false: being recorded, or its recorder never finished it
    bool interrupted = false;      ///< it ended before it was meant to
    std::string interrupted_by;    ///< why: "SIGTERM", "the studio exited", ...
    std::uint64_t clipped_samples = 0;  ///< samples of take.wav at or beyond full scale
    double peak = 0;                    ///< the largest |sample| the model played
    /// Samples played but lost by the recorder, whose writer fell behind (a slow disk, very
    /// many probes): take.wav and probes.csv miss them, so the take does not re-render to its
    /// take.wav. Written only when not 0 (an older Archet reads a take without).
    std::uint64_t dropped_samples = 0;
    /// Gesture positions and parameter changes lost the same way: the re-render lacks them.
    std::uint64_t dropped_events = 0;
    int scheme = kSchemeRevision;  ///< the scheme revision it was played with
};

/// A parameter change made while playing: it starts gliding at master tick `tick`, before
/// that tick's step, and arrives over `glide_samples` steps.
struct ParameterChange {
    std::uint64_t tick = 0;
    std::string parameter;  ///< ELEMENT.PARAM
    double value = 0;
    int glide_samples = 1;
    /// A glide already under way when the take began (at its first tick): it left `from`
    /// and has made `done` of its `glide_samples` steps. Written as "from" and "done".
    std::optional<double> from;
    int done = 0;
};

std::string format_take(const TakeDescription& take);
/// Reads take.json's text; `source` names it in errors. Older takes (without "complete",
/// "interrupted", "clipped_samples", "peak", "scheme") read as complete and uninterrupted,
/// played with scheme revision 1; a take without "dropped_samples" or "dropped_events" lost
/// nothing.
TakeDescription parse_take(const std::string& text, const std::string& source);
TakeDescription read_take_file(const std::filesystem::path& path);

std::string format_parameter_changes(const std::vector<ParameterChange>& changes);
/// Throws InputError at `where` unless a glide under way has made 0 … glide_samples − 1 steps.
void check_in_flight(const ParameterChange& change, const std::string& where);
std::vector<ParameterChange> parse_parameter_changes(const std::string& text,
                                                     const std::string& source);
std::vector<ParameterChange> read_parameter_changes(const std::filesystem::path& path);

}  // namespace archet
