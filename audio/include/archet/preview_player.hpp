#pragma once
// The studio's preview path: plays one rendered sound once (a compare view's variant, a point
// of the playability map, a recorded take) on an audio output of its own. It is apart from the
// live instrument on purpose: the engine process plays the model in real time, and a preview
// neither goes through it nor waits on it, so listening back works with the engine stopped,
// restarting or busy, and never disturbs its timing. It opens the first output that opens
// (JACK, PulseAudio, ALSA), else a null sink clocked in real time (said in description()).
// The samples are copied in before the output starts; the callback only reads them and moves
// an atomic position. Qt-free: the studio's panels hold one each.

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "archet/audio_output.hpp"

namespace archet {

class PreviewPlayer : private AudioRenderer {
  public:
    PreviewPlayer() = default;
    ~PreviewPlayer() override;
    PreviewPlayer(const PreviewPlayer&) = delete;
    PreviewPlayer& operator=(const PreviewPlayer&) = delete;

    /// Starts `samples` (at `sample_rate`, clamped to ±1) from the beginning, replacing what
    /// was playing.
    void play(const std::vector<double>& samples, double sample_rate);
    void stop();
    bool playing() const { return output_ != nullptr && position_.load() < samples_.size(); }
    /// Where the sound goes (and why, when no device opened).
    const std::string& description() const { return description_; }
    /// Frames played so far.
    std::size_t position() const { return position_.load(); }

  private:
    void render(float* out, int frames, int channels) override;

    std::unique_ptr<AudioOutput> output_;
    std::vector<float> samples_;
    std::atomic<std::size_t> position_{0};
    std::string description_;
};

}  // namespace archet
