#pragma once
// What a take's recorder leaves while it records, and how `archet render --take` recovers a
// take whose recorder never finished it (killed, crashed): take.json, written at the start,
// says `"complete": false`; take.wav's header counts only up to its last refresh (once a
// second) though its samples run on; the gesture and the parameter changes are streamed one
// line each (gesture.jsonl, parameters.jsonl), every line on disk before the samples that
// depend on it. recover_take() repairs take.wav's header, writes gesture.json and
// parameters.json from the streams and take.json as a finished take marked interrupted, so
// that the take re-renders every sample that was recorded.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "archet/files/take_file.hpp"
#include "archet/model/gesture.hpp"

namespace archet {

/// Where a WAV file's samples are, read from its first bytes and its size.
struct WavLayout {
    std::uint64_t data_offset = 0;  ///< the first sample's byte
    std::uint32_t block_align = 0;  ///< bytes per frame
    std::uint16_t bits = 0;         ///< per sample
    std::uint16_t channels = 0;
    std::uint32_t format = 0;         ///< 1: integer PCM
    std::uint64_t header_frames = 0;  ///< frames the data chunk's size counts
    std::uint64_t frames = 0;         ///< whole frames the file holds from data_offset on
};
/// `head`: the file's first bytes (at least up to its data chunk). Throws InputError naming
/// `source` when they are not a WAV file's.
WavLayout parse_wav_layout(std::string_view head, std::uint64_t file_size,
                           const std::string& source);

/// The streams: one JSON array per line, `[time, slide, press]` and
/// `[tick, "ELEMENT.PARAMETER", value, glide_samples]`. A last line without its newline was
/// being written when the recorder stopped, and is left out.
std::string format_gesture_line(const GestureKeyframe& keyframe);
std::vector<GestureKeyframe> parse_gesture_stream(std::string_view text, const std::string& source);
std::string format_parameter_line(const ParameterChange& change);
std::vector<ParameterChange> parse_parameter_stream(std::string_view text,
                                                    const std::string& source);

/// Held by a take's recorder while it records (an advisory lock on the folder, released by
/// the kernel however the process ends). held() says whether this one got it.
class TakeFolderLock {
  public:
    explicit TakeFolderLock(const std::filesystem::path& folder);
    ~TakeFolderLock();
    TakeFolderLock(const TakeFolderLock&) = delete;
    TakeFolderLock& operator=(const TakeFolderLock&) = delete;
    bool held() const { return held_; }

  private:
    int fd_ = -1;
    bool held_ = false;
};

struct RecoveredTake {
    TakeDescription take;             ///< as take.json now says: complete and interrupted
    std::uint64_t header_frames = 0;  ///< what take.wav's header said before the repair
};
/// Finishes a take its recorder left incomplete (take.json's "complete" is false). Refuses a
/// take still being recorded. Throws InputError naming the file at fault.
RecoveredTake recover_take(const std::filesystem::path& folder);

}  // namespace archet
