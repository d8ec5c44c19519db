#pragma once
// Where live sound goes: an audio device through RtAudio (JACK, ALSA, PulseAudio), or a null
// sink clocked in real time when there is none. Either calls the renderer on its real-time
// thread once per block and measures the callbacks.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace archet {

/// Fills a block on the real-time thread: no allocation, no lock, no I/O.
class AudioRenderer {
  public:
    virtual ~AudioRenderer() = default;
    /// `out` is interleaved, frames × channels.
    virtual void render(float* out, int frames, int channels) = 0;
};

struct AudioConfig {
    std::string api = "null";  ///< null, jack, alsa or pulse
    int device = -1;           ///< device index of that API; −1 for its default
    int buffer_frames = 64;
    double sample_rate = 48000;
    int channels = 2;
};

struct AudioStats {
    std::uint64_t callbacks = 0;
    std::uint64_t xruns = 0;        ///< reported by the device, or missed deadlines
    double worst_callback_us = 0;   ///< longest time spent rendering one block
    double callback_budget_us = 0;  ///< one block's duration
    double busy_us = 0;             ///< all the time spent rendering blocks so far
};

class AudioOutput {
  public:
    virtual ~AudioOutput() = default;
    virtual void start(AudioRenderer& renderer) = 0;
    virtual void stop() = 0;
    virtual AudioStats stats() const = 0;
    virtual double sample_rate() const = 0;
    virtual int buffer_frames() const = 0;
    virtual std::string description() const = 0;
    /// Whether the real-time thread got real-time scheduling, in words (after start()).
    virtual std::string scheduling() const = 0;
};

/// Opens the output the config asks for. A device API that cannot be opened falls back to the
/// null sink; `warning` then says why. Unknown APIs and bad numbers are InputErrors.
std::unique_ptr<AudioOutput> open_audio_output(const AudioConfig& config, std::string* warning);

/// An output device, as `archet devices` lists it.
struct AudioDeviceInfo {
    std::string api;  ///< what --audio takes: jack, alsa, pulse or null
    int index = 0;    ///< what --device takes
    std::string name;
    int channels = 0;             ///< output channels
    std::vector<unsigned> rates;  ///< Hz it offers
    bool is_default = false;      ///< the API's default output
};

/// One compiled API's output devices, or why it could not be asked.
struct AudioApiDevices {
    std::string api;
    std::vector<AudioDeviceInfo> devices;
    std::string unavailable;  ///< RtAudio's reason; empty when the API answered
};

/// Each compiled API's output devices, then the null sink (always available).
std::vector<AudioApiDevices> list_audio_devices();

/// "api index: name (2 out, 44100/48000 Hz) default", or "null 0: null sink (always
/// available)".
std::string describe(const AudioDeviceInfo& device);

/// An API's lines in `archet devices`: one per device, else "api: no devices" or
/// "api: unavailable (why)".
std::vector<std::string> describe(const AudioApiDevices& api);

}  // namespace archet
