#include "archet/sound_file_writer.hpp"

#include <sndfile.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <system_error>

#include "archet/common/input_error.hpp"
#include "archet/files/output_target.hpp"

namespace archet {

SoundFormat parse_sound_format(const std::string& text) {
    if (text == "wav") return SoundFormat::Wav;
    if (text == "flac") return SoundFormat::Flac;
    throw InputError("--format", "\"" + text + "\" is not a sound format; use wav or flac");
}

std::string gain_advice(double peak) {
    std::ostringstream s;
    s << "lower the model's output_gain by at least "
      << std::max(0.1, std::ceil(20 * std::log10(std::max(peak, 1.0)) * 10) / 10)
      << " dB (the \"output_gain\" field of the model file)";
    return s.str();
}

SoundFileWriter::SoundFileWriter(std::filesystem::path path, SoundFormat format, int sample_rate,
                                 WriteMode mode)
    : path_(std::move(path)), mode_(mode) {
    if (mode == WriteMode::Direct && std::filesystem::exists(path_))
        throw InputError(path_.string(), "already exists; a take never overwrites a file");
    if (mode_ == WriteMode::Safe) {
        // A device or FIFO (/dev/null, a pipe) is written in place, never renamed over.
        const OutputTarget target = output_target(path_);
        if (target.in_place) mode_ = WriteMode::Direct;
        temp_ = target.in_place ? target.path : target.temporary();
        final_ = target.path;
    } else {
        temp_ = final_ = path_;
    }
    SF_INFO info{};
    info.samplerate = sample_rate;
    info.channels = 1;
    info.format = format == SoundFormat::Wav ? (SF_FORMAT_WAV | SF_FORMAT_PCM_24)
                                             : (SF_FORMAT_FLAC | SF_FORMAT_PCM_24);
    file_ = sf_open(temp_.c_str(), SFM_WRITE, &info);
    if (!file_) {
        const std::string why = sf_strerror(nullptr);
        // libsndfile may have created the file before refusing the format: it was ours (a
        // device written in place is not a file of ours to remove).
        std::error_code ignored;
        if (std::filesystem::is_regular_file(temp_, ignored))
            std::filesystem::remove(temp_, ignored);
        throw InputError(
            path_.string(),
            "cannot write the sound file: " + why +
                (temp_ == path_ ? std::string()
                                : " (is the folder writable, and does the format take " +
                                      std::to_string(sample_rate) + " Hz?)"));
    }
    // Saturate rather than wrap around when a sample is beyond full scale.
    sf_command(file_, SFC_SET_CLIPPING, nullptr, SF_TRUE);
}

SoundFileWriter::~SoundFileWriter() {
    if (file_) {
        sf_close(file_);
        std::error_code ignored;
        if (mode_ == WriteMode::Safe) std::filesystem::remove(temp_, ignored);
    }
}

void SoundFileWriter::update_header() {
    if (file_) sf_command(file_, SFC_UPDATE_HEADER_NOW, nullptr, 0);
}

void SoundFileWriter::write(const double* samples, std::size_t count) {
    for (std::size_t i = 0; i < count; ++i) {
        const double a = std::abs(samples[i]);
        peak_ = std::max(peak_, a);
        if (a >= 1.0) ++clipped_;  // 24-bit PCM ends just below 1.0: full scale is clipped
    }
    if (sf_write_double(file_, samples, static_cast<sf_count_t>(count)) !=
        static_cast<sf_count_t>(count))
        throw InputError(path_.string(), std::string("write failed: ") + sf_strerror(file_) +
                                             "; the existing file is untouched");
    frames_ += count;
}

void SoundFileWriter::close() {
    if (!file_) return;
    const int status = sf_close(file_);
    file_ = nullptr;
    std::error_code ec;
    if (status != 0) {
        if (mode_ == WriteMode::Safe) std::filesystem::remove(temp_, ec);
        throw InputError(path_.string(), "could not finish the sound file (disk full?)");
    }
    if (mode_ == WriteMode::Direct) return;
    std::filesystem::rename(temp_, final_, ec);
    if (ec) {
        std::filesystem::remove(temp_, ec);
        throw InputError(path_.string(), "cannot move the sound file into place: " + ec.message());
    }
}

}  // namespace archet
