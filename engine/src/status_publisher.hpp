#pragma once
// The engine's status frames to the studio: what a command did, what went wrong, and every
// 50 ms a heartbeat with the real-time thread's counters and load.
//
// Ownership: the control thread's alone (it is the status ring's only producer); it reads the
// real-time thread's counters from ThreadBridge and the device's statistics.

#include <chrono>
#include <cstdint>
#include <string>

#include "archet/audio_output.hpp"
#include "archet/ipc/segment_layout.hpp"
#include "archet/ipc/spsc_ring.hpp"
#include "thread_bridge.hpp"

namespace archet {

class StatusPublisher {
  public:
    StatusPublisher(const ThreadBridge& bridge, ipc::SpscRing<ipc::StatusFrame> status,
                    ipc::SpscRing<ipc::ProbeFrame> probes)
        : bridge_(bridge), status_(status), probes_(probes) {}

    /// The device whose statistics the frames carry, once it is open.
    void nrt_set_output(const AudioOutput* output) { output_ = output; }
    void nrt_publish(ipc::StatusKind kind, std::uint32_t sequence, const std::string& text);

  private:
    double nrt_measure_load(const AudioStats& audio);

    static constexpr double kLoadWindowUs = 200'000;
    const ThreadBridge& bridge_;
    ipc::SpscRing<ipc::StatusFrame> status_;
    ipc::SpscRing<ipc::ProbeFrame> probes_;  ///< only for the frames the studio dropped
    const AudioOutput* output_ = nullptr;
    std::chrono::steady_clock::time_point load_measured_at_{};  ///< the last measurement
    double load_busy_us_ = 0, load_ = 0;
};

}  // namespace archet
