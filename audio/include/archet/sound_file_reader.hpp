#pragma once
// Reads a sound file (WAV, FLAC) into memory, mixed down to mono: for playing back takes and
// exporting them in another format.

#include <filesystem>
#include <vector>

namespace archet {

struct SoundData {
    std::vector<double> samples;
    double sample_rate = 0;
};

/// Throws InputError naming the file when it cannot be read.
SoundData read_sound_file(const std::filesystem::path& path);

}  // namespace archet
