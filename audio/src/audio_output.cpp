#include "archet/audio_output.hpp"

#include <pthread.h>
#include <rtaudio/RtAudio.h>
#include <time.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <thread>

#include "archet/common/input_error.hpp"
#include "archet/common/monotonic_clock.hpp"
#include "archet/realtime_thread_mark.hpp"

namespace archet {

namespace {

// Shared measurement of callbacks (written on the real-time thread only).
struct CallbackMeter {
    std::atomic<std::uint64_t> callbacks{0}, xruns{0}, worst_ns{0}, busy_ns{0};
    void record(std::int64_t spent) {
        callbacks.fetch_add(1, std::memory_order_relaxed);
        const auto ns = static_cast<std::uint64_t>(std::max<std::int64_t>(spent, 0));
        busy_ns.fetch_add(ns, std::memory_order_relaxed);
        if (ns > worst_ns.load(std::memory_order_relaxed))
            worst_ns.store(ns, std::memory_order_relaxed);
    }
    AudioStats stats(double budget_us) const {
        return {callbacks.load(), xruns.load(), static_cast<double>(worst_ns.load()) / 1000.0,
                budget_us, static_cast<double>(busy_ns.load()) / 1000.0};
    }
};

// No device: a thread that wakes at absolute block deadlines, as a sound card would call.
class NullOutput final : public AudioOutput {
  public:
    NullOutput(double rate, int frames, int channels)
        : rate_(rate), frames_(frames), channels_(channels) {}
    ~NullOutput() override { stop(); }

    void start(AudioRenderer& renderer) override {
        renderer_ = &renderer;
        buffer_.assign(static_cast<std::size_t>(frames_ * channels_), 0.0f);
        running_.store(true);
        thread_ = std::thread([this] { loop(); });
        while (scheduling_.load() < 0) std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
    void stop() override {
        if (running_.exchange(false) && thread_.joinable()) thread_.join();
    }
    AudioStats stats() const override { return meter_.stats(1e6 * frames_ / rate_); }
    double sample_rate() const override { return rate_; }
    int buffer_frames() const override { return frames_; }
    std::string description() const override {
        return "null sink (no device, clocked in real time)";
    }
    std::string scheduling() const override {
        return scheduling_.load() == 1
                   ? "real-time scheduling granted"
                   : "real-time scheduling not permitted (raise the user's rtprio "
                     "limit or grant CAP_SYS_NICE); running at normal priority";
    }

  private:
    void loop() {
        sched_param param{};
        param.sched_priority = 70;
        scheduling_.store(pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0 ? 1 : 0);
        const RealtimeThreadMark mark;  // until the loop ends: the thread's exit is not counted
        const auto period = static_cast<std::int64_t>(1e9 * frames_ / rate_);
        std::int64_t deadline = monotonic_ns();
        while (running_.load(std::memory_order_relaxed)) {
            deadline += period;
            timespec t{static_cast<time_t>(deadline / 1'000'000'000),
                       static_cast<long>(deadline % 1'000'000'000)};
            while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, nullptr) == EINTR) {
            }
            const std::int64_t start = monotonic_ns();
            if (start - deadline > period) {  // a whole block late: the device would have glitched
                meter_.xruns.fetch_add(1, std::memory_order_relaxed);
                deadline = start;
            }
            renderer_->render(buffer_.data(), frames_, channels_);
            meter_.record(monotonic_ns() - start);
        }
    }

    double rate_;
    int frames_, channels_;
    AudioRenderer* renderer_ = nullptr;
    std::vector<float> buffer_;
    std::atomic<bool> running_{false};
    std::atomic<int> scheduling_{-1};  ///< −1 unknown, 0 refused, 1 granted
    std::thread thread_;
    CallbackMeter meter_;
};

RtAudio::Api api_of(const std::string& name) {
    if (name == "jack") return RtAudio::UNIX_JACK;
    if (name == "alsa") return RtAudio::LINUX_ALSA;
    if (name == "pulse") return RtAudio::LINUX_PULSE;
    throw InputError("--audio",
                     "\"" + name + "\" is not an audio API; use jack, alsa, pulse, auto or null");
}

class DeviceOutput final : public AudioOutput {
  public:
    DeviceOutput(const AudioConfig& c) : audio_(api_of(c.api)), config_(c) {
        audio_.showWarnings(false);
        if (audio_.getDeviceCount() == 0)
            throw RtAudioError("no output device", RtAudioError::NO_DEVICES_FOUND);
        RtAudio::StreamParameters out;
        out.deviceId =
            c.device >= 0 ? static_cast<unsigned>(c.device) : audio_.getDefaultOutputDevice();
        if (out.deviceId >= audio_.getDeviceCount())
            throw InputError("--device", std::to_string(c.device) + " is not a device of " + c.api +
                                             " (it has " + std::to_string(audio_.getDeviceCount()) +
                                             "); see archet devices");
        out.nChannels = static_cast<unsigned>(c.channels);
        unsigned frames = static_cast<unsigned>(c.buffer_frames);
        RtAudio::StreamOptions options;
        options.flags = RTAUDIO_MINIMIZE_LATENCY | RTAUDIO_SCHEDULE_REALTIME;
        options.priority = 70;
        options.streamName = "archet";
        audio_.openStream(&out, nullptr, RTAUDIO_FLOAT32, static_cast<unsigned>(c.sample_rate),
                          &frames, &DeviceOutput::callback, this, &options);
        config_.buffer_frames = static_cast<int>(frames);
        config_.sample_rate = audio_.getStreamSampleRate();
        name_ = c.api + " device " + std::to_string(out.deviceId) + " \"" +
                audio_.getDeviceInfo(out.deviceId).name + "\"";
    }
    ~DeviceOutput() override {
        stop();
        if (audio_.isStreamOpen()) audio_.closeStream();
    }
    void start(AudioRenderer& renderer) override {
        renderer_ = &renderer;
        audio_.startStream();
    }
    void stop() override {
        if (audio_.isStreamRunning()) audio_.stopStream();
    }
    AudioStats stats() const override {
        return meter_.stats(1e6 * config_.buffer_frames / config_.sample_rate);
    }
    double sample_rate() const override { return config_.sample_rate; }
    int buffer_frames() const override { return config_.buffer_frames; }
    std::string description() const override { return name_; }
    std::string scheduling() const override {
        return config_.api == "jack" ? "scheduled by the JACK server"
                                     : "real-time scheduling requested from the driver";
    }

  private:
    static int callback(void* out, void*, unsigned frames, double, RtAudioStreamStatus status,
                        void* self) {
        auto* me = static_cast<DeviceOutput*>(self);
        mark_realtime_thread();  // the driver's thread: counted if anything allocates here
        const std::int64_t start = monotonic_ns();
        if (status & RTAUDIO_OUTPUT_UNDERFLOW)
            me->meter_.xruns.fetch_add(1, std::memory_order_relaxed);
        me->renderer_->render(static_cast<float*>(out), static_cast<int>(frames),
                              me->config_.channels);
        me->meter_.record(monotonic_ns() - start);
        return 0;
    }

    RtAudio audio_;
    AudioConfig config_;
    std::string name_;
    AudioRenderer* renderer_ = nullptr;
    CallbackMeter meter_;
};

}  // namespace

std::unique_ptr<AudioOutput> open_audio_output(const AudioConfig& c, std::string* warning) {
    if (c.buffer_frames < 1 || c.buffer_frames > 8192)
        throw InputError("--buffer", "must be 1 to 8192 frames");
    if (!(c.sample_rate >= 8000 && c.sample_rate <= 384000))
        throw InputError("--rate", "must be 8000 to 384000 Hz");
    if (c.channels < 1 || c.channels > 32) throw InputError("channels", "must be 1 to 32");
    if (c.api == "null")
        return std::make_unique<NullOutput>(c.sample_rate, c.buffer_frames, c.channels);
    if (c.api == "auto") {  // the first that opens: a JACK server, then PulseAudio, then ALSA
        std::string tried;
        for (const char* api : {"jack", "pulse", "alsa"}) {
            AudioConfig attempt = c;
            attempt.api = api;
            try {
                return std::make_unique<DeviceOutput>(attempt);
            } catch (const RtAudioError& e) {
                tried += (tried.empty() ? "" : "; ") + std::string(api) + ": " + e.getMessage();
            }
        }
        if (warning) *warning = "no audio output opened (" + tried + "); playing into a null sink";
        return std::make_unique<NullOutput>(c.sample_rate, c.buffer_frames, c.channels);
    }
    api_of(c.api);  // unknown names are the user's mistake, not a missing device
    try {
        return std::make_unique<DeviceOutput>(c);
    } catch (const RtAudioError& e) {
        if (warning)
            *warning = "cannot open " + c.api + " output (" + e.getMessage() +
                       "); playing into a null sink instead";
        return std::make_unique<NullOutput>(c.sample_rate, c.buffer_frames, c.channels);
    }
}

std::vector<AudioApiDevices> list_audio_devices() {
    std::vector<AudioApiDevices> found;
    std::vector<RtAudio::Api> apis;
    RtAudio::getCompiledApi(apis);
    for (RtAudio::Api api : apis) {
        AudioApiDevices& listed = found.emplace_back();
        listed.api = RtAudio::getApiName(api);
        try {
            RtAudio audio(api);
            audio.showWarnings(false);
            const unsigned count = audio.getDeviceCount();
            for (unsigned i = 0; i < count; ++i) {
                const RtAudio::DeviceInfo info = audio.getDeviceInfo(i);
                if (!info.probed || info.outputChannels == 0) continue;
                listed.devices.push_back({listed.api, static_cast<int>(i), info.name,
                                          static_cast<int>(info.outputChannels), info.sampleRates,
                                          info.isDefaultOutput});
            }
        } catch (const RtAudioError& e) {
            listed.unavailable = e.getMessage();
        }
    }
    found.push_back({"null", {{"null", 0, "null sink", 0, {}, true}}, {}});
    return found;
}

std::string describe(const AudioDeviceInfo& d) {
    if (d.api == "null") return "null 0: null sink (always available)";
    std::string rates;
    for (unsigned r : d.rates) rates += (rates.empty() ? "" : "/") + std::to_string(r);
    return d.api + " " + std::to_string(d.index) + ": " + d.name + " (" +
           std::to_string(d.channels) + " out, " + rates + " Hz)" +
           (d.is_default ? " default" : "");
}

std::vector<std::string> describe(const AudioApiDevices& api) {
    if (!api.unavailable.empty()) return {api.api + ": unavailable (" + api.unavailable + ")"};
    if (api.devices.empty()) return {api.api + ": no devices"};
    std::vector<std::string> lines;
    for (const AudioDeviceInfo& d : api.devices) lines.push_back(describe(d));
    return lines;
}

}  // namespace archet
