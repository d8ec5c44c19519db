#pragma once
// Writes mono audio to WAV (24-bit PCM) or FLAC through libsndfile. Writes to a temporary
// file beside the target and renames it on close, so an existing file is never left
// half-written. Counts samples beyond full scale instead of clipping silently.

#include <cstdint>
#include <filesystem>
#include <string>

struct sf_private_tag;

namespace archet {

enum class SoundFormat { Wav, Flac };

/// Safe: through a temporary file renamed on close (never a half-written file of the user's).
/// Direct: straight into a new file that must not exist yet, its header kept current by
/// update_header(), so that a crash leaves a valid file up to the last update (takes).
enum class WriteMode { Safe, Direct };

/// What to change when a sound of this peak clipped: "lower the model's output_gain by ...".
std::string gain_advice(double peak);

/// Parses "wav" / "flac"; throws InputError otherwise.
SoundFormat parse_sound_format(const std::string& text);

class SoundFileWriter {
  public:
    SoundFileWriter(std::filesystem::path path, SoundFormat format, int sample_rate,
                    WriteMode mode = WriteMode::Safe);
    ~SoundFileWriter();
    SoundFileWriter(const SoundFileWriter&) = delete;
    SoundFileWriter& operator=(const SoundFileWriter&) = delete;

    void write(const double* samples, std::size_t count);
    /// Finishes the file and moves it into place.
    void close();
    /// Rewrites the header for what has been written so far (WAV).
    void update_header();

    std::uint64_t clipped_samples() const { return clipped_; }  ///< at or beyond full scale
    double peak() const { return peak_; }
    std::uint64_t frames() const { return frames_; }

  private:
    std::filesystem::path path_, temp_, final_;  ///< as given, written, renamed onto
    WriteMode mode_;
    sf_private_tag* file_ = nullptr;
    std::uint64_t clipped_ = 0, frames_ = 0;
    double peak_ = 0;
};

}  // namespace archet
