#include "archet/sound_file_reader.hpp"

#include <sndfile.h>

#include "archet/common/input_error.hpp"

namespace archet {

SoundData read_sound_file(const std::filesystem::path& path) {
    SF_INFO info{};
    SNDFILE* file = sf_open(path.c_str(), SFM_READ, &info);
    if (!file)
        throw InputError(path.string(), std::string("cannot read it: ") + sf_strerror(nullptr));
    std::vector<double> frames(static_cast<std::size_t>(info.frames) *
                               static_cast<std::size_t>(info.channels));
    const sf_count_t read = sf_readf_double(file, frames.data(), info.frames);
    sf_close(file);
    SoundData data;
    data.sample_rate = info.samplerate;
    data.samples.resize(static_cast<std::size_t>(read));
    for (std::size_t i = 0; i < data.samples.size(); ++i) {
        double sum = 0;
        for (int c = 0; c < info.channels; ++c) sum += frames[i * info.channels + c];
        data.samples[i] = sum / info.channels;
    }
    return data;
}

}  // namespace archet
