#pragma once
// Records a live take into a folder: take.wav (the model's output, as `archet render` writes
// it), probes.csv, gesture.json (the device positions the model actually played), model.json,
// and, when it began mid-performance, state.bin (the model's state at its first sample) and
// parameters.json (the changes made while recording); take.json ties them together (see
// take_file.hpp). The real-time side only copies into lock-free rings and a buffer sized in
// advance; a writer thread does the file work. model.json and take.json ("complete": false)
// are written at the start; samples go straight into take.wav and probes.csv, the gesture and
// parameter changes into gesture.jsonl and parameters.jsonl, each line on disk before the
// samples that follow it, and the WAV header is refreshed every second. So a take killed
// outright is recovered by `archet render --take DIR` (take_recovery.hpp); a finished one,
// interrupted or not, is reproduced by it exactly. The folder is locked while it records.

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "archet/files/take_file.hpp"
#include "archet/files/take_recovery.hpp"
#include "archet/ipc/record_ring.hpp"
#include "archet/ipc/spsc_ring.hpp"
#include "archet/model/gesture.hpp"
#include "archet/model/model.hpp"
#include "archet/physics/parameter_smoother.hpp"
#include "archet/probe_csv_writer.hpp"
#include "archet/sound_file_writer.hpp"

namespace archet {

class TakeRecorder {
  public:
    /// Creates the folder (it must not exist, or be empty), writes model.json (`played`, at
    /// the rate it plays) and starts the writer thread. `state_size` > 0 makes room for a
    /// state saved where the take begins (Simulation::state_size()).
    TakeRecorder(std::filesystem::path folder, const Model& played, double sample_rate,
                 std::vector<std::string> probe_names, std::size_t state_size = 0);
    ~TakeRecorder();  ///< finishes the take
    TakeRecorder(const TakeRecorder&) = delete;
    TakeRecorder& operator=(const TakeRecorder&) = delete;

    // ---- control thread ----
    /// A number for a parameter name, to pass to parameter() from the real-time side.
    std::uint32_t parameter_name(const std::string& element_dot_parameter);
    /// The name of a slot a glide may be under way in when the take begins (before it is
    /// handed to the real-time thread).
    void name_slot(const ParameterSlot& slot, const std::string& element_dot_parameter);

    // ---- real-time side: no allocation, no I/O ----
    /// Where Simulation::save_state() writes the state at the take's start (null without).
    double* state_buffer() { return state_.empty() ? nullptr : state_.data(); }
    /// The take's first sample will be master tick `tick` (call once, before sample()).
    void begin(std::uint64_t tick);
    /// One audio-rate sample: the model's output and its `count` probe values (one for each
    /// probe name). A non-finite output ends what the take holds there; finish() then says the
    /// simulation stopped being finite.
    void sample(double time, double output, const double* probes, std::size_t count);
    /// A device position the gesture points took, at the time they took it.
    void gesture(double time, GestureSample position);
    /// A parameter change that starts gliding at `tick`.
    void parameter(std::uint64_t tick, std::uint32_t name, double value, int glide_samples);
    /// A glide under way at the take's first tick (call after begin(), before sample()).
    void glide_under_way(const ParameterSmoother::Glide& glide);
    /// While the take waits to begin: a change the control thread named for it (name from
    /// parameter_name()) has started gliding `slot`.
    void name_slot_waiting(const ParameterSlot& slot, std::uint32_t name);

    /// Stops, writes what is left, closes the files. `interrupted_by`, when not empty, says
    /// why the take ended before it was meant to ("SIGTERM"): take.json records it. Throws if
    /// a file could not be written.
    void finish(const std::string& interrupted_by = {});
    /// Samples lost because the writer fell behind (a slow disk, very many probes).
    std::uint64_t dropped_samples() const;
    /// Gesture positions and parameter changes lost the same way, and glides under way whose
    /// parameter nobody named.
    std::uint64_t dropped_events() const;
    std::uint64_t frames() const { return frames_.load(); }
    const std::filesystem::path& folder() const { return folder_; }
    /// After finish(): the samples at or beyond full scale, and the peak.
    std::uint64_t clipped_samples() const { return clipped_; }
    double peak() const { return peak_; }
    /// After finish(): a sentence for the player when the take clipped, else empty.
    std::string clipping_note() const;
    /// A sentence for the player when the take lost samples or events (take.json counts them),
    /// else empty: such a take does not re-render to its take.wav.
    std::string incomplete_note() const;

  private:
    struct Change {
        std::uint64_t tick;
        std::uint32_t name;
        int glide_samples;
        double value;
        bool under_way = false;  ///< a glide the take began among: from and done below
        double from = 0;
        int done = 0;
    };
    void write_loop();
    TakeDescription description() const;
    std::vector<ParameterChange> named(const std::vector<Change>& changes);
    void write_description(std::vector<GestureKeyframe> keyframes,
                           const std::vector<Change>& changes);

    std::filesystem::path folder_;
    std::unique_ptr<TakeFolderLock> lock_;
    double sample_rate_;
    std::vector<std::string> probe_names_;
    std::unique_ptr<SoundFileWriter> wav_;
    std::unique_ptr<ProbeCsvWriter> csv_;
    std::FILE* gesture_stream_ = nullptr;    ///< gesture.jsonl, writer thread
    std::FILE* parameter_stream_ = nullptr;  ///< parameters.jsonl, opened at the first change
    /// Each sample as its time, the output and every probe's value, in the model's order.
    ipc::RecordRing samples_;
    ipc::LocalRing<GestureKeyframe> gestures_;
    ipc::LocalRing<Change> changes_;
    std::vector<double> state_;
    std::atomic<std::uint64_t> start_tick_{0};
    std::atomic<bool> begun_{false};
    std::atomic<std::uint64_t> frames_{0};
    /// The time of the first non-finite output sample, or below 0: from there the take holds
    /// nothing more (NaN would be written as full-scale DC).
    std::atomic<double> blown_up_at_{-1.0};
    static_assert(std::atomic<double>::is_always_lock_free);
    std::mutex names_mutex_;  ///< control and writer threads only
    std::vector<std::string> names_;
    /// Slots named before the take began: by the control thread before it hands the take over,
    /// then by the real-time side alone, within the capacity reserved.
    std::vector<std::pair<ParameterSlot, std::uint32_t>> slot_names_;
    static constexpr std::size_t kSlotNames = 256;
    std::atomic<std::uint64_t> unnamed_glides_{0};  ///< under way in a slot nobody named
    std::atomic<bool> stopping_{false};
    std::thread writer_;
    std::string error_;
    std::string interrupted_by_;  ///< set before the writer's last round
    std::uint64_t clipped_ = 0;   ///< after the writer ends
    double peak_ = 0;
    bool finished_ = false;
};

}  // namespace archet
