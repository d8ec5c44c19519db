#pragma once
// Plays a rendered sound once (A/B listening in the compare view, take playback) on its own
// audio output: the first device that opens, else a null sink clocked in real time (said in
// description()). The samples are copied in before playing; the callback only reads them.

#include <QString>
#include <atomic>
#include <memory>
#include <vector>

#include "archet/audio_output.hpp"

namespace archet::ui {

class SoundPlayer : private AudioRenderer {
  public:
    SoundPlayer() = default;
    ~SoundPlayer() override;

    /// Starts `samples` (at `sample_rate`) from the beginning, replacing what was playing.
    void play(std::vector<double> samples, double sample_rate);
    void stop();
    bool playing() const { return position_.load() < samples_.size() && output_ != nullptr; }
    /// Where the sound goes (and why, when no device opened).
    QString description() const { return description_; }
    std::size_t position() const { return position_.load(); }

  private:
    void render(float* out, int frames, int channels) override;

    std::unique_ptr<AudioOutput> output_;
    std::vector<float> samples_;
    std::atomic<std::size_t> position_{0};
    QString description_;
};

}  // namespace archet::ui
