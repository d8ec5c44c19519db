#pragma once
// The engine's real-time thread: the audio device's callback, once per block. It swaps in a
// model at a block boundary, applies parameter changes, steps the simulation, limits the
// output, publishes probe and shape frames, cross-fades models and mutes a blow-up. It does not
// allocate, lock, log or do I/O: whatever needs that goes back to the control thread through
// ThreadBridge.
//
// Ownership: every rt_ member is the real-time thread's alone while the device runs (the
// running and the fading model, the take it feeds or waits to begin, the smoother, the pad,
// the studio's fade, the limiter, the probe and shape rings it produces). The const members
// are set by the control thread before the device starts, then only read; `bridge_` is shared
// (ThreadBridge). The nrt_ functions are the control thread's, for after the device stopped.

#include <array>
#include <cstdint>
#include <memory>

#include "archet/audio_output.hpp"
#include "archet/ipc/segment_layout.hpp"
#include "archet/ipc/spsc_ring.hpp"
#include "archet/model/gesture.hpp"
#include "archet/output_limiter.hpp"
#include "archet/physics/parameter_smoother.hpp"
#include "loaded_model.hpp"
#include "thread_bridge.hpp"

namespace archet {

class RealtimeThread final : public AudioRenderer {
  public:
    struct Setup {
        double sample_rate;      ///< the device's
        int shape_every;         ///< blocks between shape frames
        bool has_haptic_device;  ///< the device, not the pad, moves the bow
    };
    /// Built by the control thread once the device is open, before it starts.
    RealtimeThread(ThreadBridge& bridge, ipc::SpscRing<ipc::ProbeFrame> probes,
                   ipc::SpscRing<ipc::ShapeFrame> shapes, const Setup& setup);
    ~RealtimeThread() override;
    RealtimeThread(const RealtimeThread&) = delete;
    RealtimeThread& operator=(const RealtimeThread&) = delete;

    /// Real-time thread: the device's callback.
    void render(float* out, int frames, int channels) override;

    /// Control thread, after the device stopped: hands the takes back to be finished.
    void nrt_hand_back_takes();
    /// Control thread, after the device stopped: deletes the models it held.
    void nrt_release_models();

  private:
    void rt_swap_in_pending();
    void rt_apply(const RealtimeCommand& r);
    void rt_begin_take();
    void rt_end_take();
    double rt_cross_fade(double incoming);
    void rt_drive_bow(Simulation& sim, const LoadedModel& m);
    bool rt_continue_into(LoadedModel& next);
    double rt_studio_fade(double output);
    void rt_mute(float* from, float* to);
    void rt_before_run(Simulation& sim, LoadedModel& m);
    int rt_run_length(const Simulation& sim, const LoadedModel& m, int left) const;
    void rt_run_block(LoadedModel& m, float* out, int frames, int channels);
    void rt_publish_shape(const LoadedModel& m);
    double rt_device_time() const { return static_cast<double>(rt_device_ticks_) / sample_rate_; }

    static constexpr double kGlideSeconds = 0.01;  ///< parameter changes arrive over 10 ms
    static constexpr double kFadeSeconds = 0.01;   ///< models swap over a 10 ms cross-fade
    /// A bowed string holds millijoules: a thousand joules means the numbers ran away.
    static constexpr double kRunawayEnergy = 1e3;

    ThreadBridge& bridge_;
    ipc::SpscRing<ipc::ProbeFrame> rt_probes_;  ///< this thread produces
    ipc::SpscRing<ipc::ShapeFrame> rt_shapes_;  ///< this thread produces
    const double sample_rate_;                  ///< the device's clock, the master
    const int shape_every_;
    const bool has_haptic_device_;
    const int fade_samples_;  ///< kFadeSeconds at the device's rate
    std::unique_ptr<OutputLimiter> rt_limiter_;

    LoadedModel* rt_running_ = nullptr;      ///< the model that plays
    LoadedModel* rt_fading_from_ = nullptr;  ///< the model being faded out
    int rt_fade_done_ = 0;
    bool rt_muted_ = false, rt_playing_ = false;
    bool rt_silent_ = false;     ///< ThreadBridge::silent for this block
    double rt_studio_gain_ = 1;  ///< fades out while the studio is silent, back in after
    int rt_shape_countdown_ = 0;
    /// Samples played since the engine started, whatever the model. The device's clock: a new
    /// model's own time starts again at 0, the device's does not.
    std::uint64_t rt_device_ticks_ = 0;
    GestureSample rt_pad_{};  ///< the pad's latest position
    /// m/s: a BowDrive slides the pad's position on at each haptic tick (MIDI's bow), so the
    /// hand moves smoothly at the points' own rate; 0 once the pad or OSC moves it.
    double rt_drive_speed_ = 0;
    TakeRecorder* rt_waiting_take_ = nullptr;  ///< to begin when it can
    std::uint64_t rt_waiting_generation_ = 0;  ///< the model it was made for
    TakeRecorder* rt_recording_ = nullptr;     ///< the take being fed
    ParameterSmoother rt_smoother_;
    /// A run's sound and probe rows (Simulation::run()): runs end at the next tick that asks
    /// for something between steps, at most this many ticks on.
    static constexpr std::uint64_t kMostTicksARun = 64;
    std::array<double, kMostTicksARun> rt_sound_{};
    std::array<double, kMostTicksARun * ipc::kMaxProbes> rt_rows_{};
};

}  // namespace archet
