#pragma once
// Records a live take into a folder: take.wav (the model's output, as `archet render` writes
// it), probes.csv, and gesture.json (the device positions the model actually played). The
// real-time side only copies into lock-free rings; a writer thread does the file work and
// refreshes the WAV header every second, so a crash leaves a valid WAV up to the last second.
// Re-rendering the model with the take's gesture reproduces the take's audio exactly.

#include <atomic>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "archet/gesture.hpp"
#include "archet/ipc/spsc_ring.hpp"
#include "archet/probe_csv_writer.hpp"
#include "archet/sound_file_writer.hpp"

namespace archet {

class TakeRecorder {
  public:
    /// Creates the folder (it must not exist, or be empty) and starts the writer thread.
    TakeRecorder(std::filesystem::path folder, double sample_rate,
                 std::vector<std::string> probe_names);
    ~TakeRecorder();  ///< finishes the take
    TakeRecorder(const TakeRecorder&) = delete;
    TakeRecorder& operator=(const TakeRecorder&) = delete;

    // ---- real-time side: no allocation, no I/O ----
    /// One audio-rate sample: the model's output and its probe values.
    void sample(double time, double output, const double* probes, std::size_t count);
    /// A device position the gesture points took, at the time they took it.
    void gesture(double time, GestureSample position);

    /// Stops, writes what is left, closes the files. Throws if a file could not be written.
    void finish();
    std::uint64_t dropped() const;  ///< samples lost because the writer fell behind
    const std::filesystem::path& folder() const { return folder_; }

  private:
    struct Sample {
        double time, output;
        std::uint32_t count;
        double probes[ipc::kMaxProbes];
    };
    void write_loop();

    std::filesystem::path folder_;
    double sample_rate_;
    std::vector<std::string> probe_names_;
    std::unique_ptr<SoundFileWriter> wav_;
    std::unique_ptr<ProbeCsvWriter> csv_;
    ipc::LocalRing<Sample> samples_;
    ipc::LocalRing<GestureKeyframe> gestures_;
    std::atomic<bool> stopping_{false};
    std::thread writer_;
    std::string error_;
    bool finished_ = false;
};

}  // namespace archet
