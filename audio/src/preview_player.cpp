#include "archet/preview_player.hpp"

#include <algorithm>

namespace archet {

namespace {
// A preview is heard, not played with: a buffer this long survives a busy desktop.
constexpr int kPreviewBufferFrames = 512;
}  // namespace

PreviewPlayer::~PreviewPlayer() {
    stop();
}

void PreviewPlayer::play(const std::vector<double>& samples, double sample_rate) {
    stop();  // the output's thread is gone: the samples are ours to replace
    samples_.assign(samples.begin(), samples.end());
    for (float& s : samples_) s = std::clamp(s, -1.0f, 1.0f);
    position_.store(0);
    AudioConfig config;
    config.api = "auto";
    config.sample_rate = sample_rate;
    config.buffer_frames = kPreviewBufferFrames;
    std::string warning;
    output_ = open_audio_output(config, &warning);
    description_ = output_->description();
    if (!warning.empty()) description_ += " — " + warning;
    output_->start(*this);
}

void PreviewPlayer::stop() {
    if (output_) output_->stop();
    output_.reset();
}

void PreviewPlayer::render(float* out, int frames, int channels) {
    std::size_t at = position_.load(std::memory_order_relaxed);
    for (int i = 0; i < frames; ++i, ++at) {
        const float y = at < samples_.size() ? samples_[at] : 0.0f;
        for (int c = 0; c < channels; ++c) out[i * channels + c] = y;
    }
    position_.store(std::min(at, samples_.size()), std::memory_order_relaxed);
}

}  // namespace archet
