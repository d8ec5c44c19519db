#pragma once
// Whether the studio that started the engine still lives and still beats. The studio's pid is
// fixed at start (later writes to the header change nothing). As its child the engine asks the
// kernel for SIGTERM when it dies; in any case it holds a pidfd, readable once the process has
// exited, or (without pidfd_open) asks kill(pid, 0). A studio whose heartbeat stops (frozen,
// stopped, stuck) cannot hear or steer: after studio_timeout the engine falls silent until it
// beats again; after studio_give_up the engine leaves (a studio that wakes then restarts it).
//
// Ownership: the control thread's alone; it tells the real-time thread to fall silent through
// ThreadBridge::silent.

#include <atomic>
#include <chrono>
#include <cstdint>

#include "archet/ipc/segment_layout.hpp"
#include "status_publisher.hpp"

namespace archet {

class StudioWatch {
  public:
    /// Starts watching `studio_pid` (asks for the death signal when it is the parent).
    StudioWatch(std::int32_t studio_pid, double timeout, double give_up, ipc::SegmentHeader& header,
                std::atomic<bool>& silent, StatusPublisher& status);
    ~StudioWatch();
    StudioWatch(const StudioWatch&) = delete;
    StudioWatch& operator=(const StudioWatch&) = delete;

    enum class Verdict {
        Stay,
        StudioExited,      ///< nobody will read or unlink the segment
        Signalled,         ///< a user's signal: the studio lives, the segment is its to remove
        HeartbeatStopped,  ///< silent for studio_give_up
    };
    /// The heartbeat as it is now: the quiet it is judged on starts here.
    void nrt_begin();
    /// One round of the control loop; `signal` is the interruption seen, if any.
    Verdict nrt_check(int signal);
    /// The studio stopped beating and the engine fell silent.
    bool nrt_silenced() const { return silenced_; }

  private:
    bool nrt_studio_gone() const;
    bool nrt_watch_heartbeat();

    static constexpr std::chrono::milliseconds kTerminateGrace{500};
    const std::int32_t studio_pid_;
    const double timeout_, give_up_;
    ipc::SegmentHeader& header_;
    std::atomic<bool>& silent_;
    StatusPublisher& status_;
    int pidfd_ = -1;                ///< readable once the studio has exited (-1: none)
    bool child_of_studio_ = false;  ///< the kernel sends SIGTERM when the studio dies
    std::chrono::steady_clock::time_point terminated_at_;  ///< when a signal was first seen
    std::chrono::steady_clock::time_point last_watch_;     ///< the previous heartbeat check
    std::uint64_t beat_ = 0;                               ///< the studio's, as last seen
    std::chrono::steady_clock::time_point beat_at_;        ///< when it last moved
    bool silenced_ = false;
};

}  // namespace archet
