#include "studio_watch.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "archet/ipc/shared_segment.hpp"

namespace archet {

using namespace ipc;

namespace {
std::string seconds_text(double seconds) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f s", seconds);
    return text;
}
}  // namespace

StudioWatch::StudioWatch(std::int32_t studio_pid, double timeout, double give_up,
                         SegmentHeader& header, std::atomic<bool>& silent, StatusPublisher& status)
    : studio_pid_(studio_pid),
      timeout_(timeout),
      give_up_(give_up),
      header_(header),
      silent_(silent),
      status_(status) {
    if (::getppid() == studio_pid_) {  // SIGTERM is handled by run_engine's guard
        ::prctl(PR_SET_PDEATHSIG, SIGTERM);
        child_of_studio_ = true;
    }
#ifdef SYS_pidfd_open
    pidfd_ = static_cast<int>(::syscall(SYS_pidfd_open, studio_pid_, 0));
#endif
}

StudioWatch::~StudioWatch() {
    if (pidfd_ >= 0) ::close(pidfd_);
}

void StudioWatch::nrt_begin() {
    beat_ = header_.studio_heartbeat.load();
    beat_at_ = last_watch_ = std::chrono::steady_clock::now();
}

// For the studio's child a signal may be the kernel's news that the studio died
// (PR_SET_PDEATHSIG), or the terminal's Ctrl+C to the whole process group: the studio's end is
// caught here, or within the grace, since the death signal comes when the studio's thread that
// started the engine exits, which can be a moment before the whole process is gone. Still
// alive after it: a user's signal.
StudioWatch::Verdict StudioWatch::nrt_check(int signal) {
    if (signal && terminated_at_ == std::chrono::steady_clock::time_point{})
        terminated_at_ = std::chrono::steady_clock::now();
    if (nrt_studio_gone()) return Verdict::StudioExited;
    if (signal &&
        (!child_of_studio_ || std::chrono::steady_clock::now() - terminated_at_ > kTerminateGrace))
        return Verdict::Signalled;
    return nrt_watch_heartbeat() ? Verdict::Stay : Verdict::HeartbeatStopped;
}

bool StudioWatch::nrt_studio_gone() const {
    if (child_of_studio_ && ::getppid() != studio_pid_) return true;  // died before prctl
    if (pidfd_ >= 0) {
        pollfd p{pidfd_, POLLIN, 0};
        return ::poll(&p, 1, 0) > 0;
    }
    return process_gone(studio_pid_);
}

// False: the engine leaves.
bool StudioWatch::nrt_watch_heartbeat() {
    const std::uint64_t beat = header_.studio_heartbeat.load();
    const auto now = std::chrono::steady_clock::now();
    // A round far later than its 2 ms: the engine itself was stopped (Ctrl+Z stops the
    // studio's whole process group) and the studio, woken with it, has had no turn yet.
    if (now - last_watch_ > std::chrono::milliseconds(500)) beat_at_ = now;
    last_watch_ = now;
    if (beat != beat_) {
        beat_ = beat;
        beat_at_ = now;
        if (silenced_) {
            silenced_ = false;
            silent_.store(false);
            header_.engine_state.store(static_cast<std::uint32_t>(EngineState::Ready));
            status_.nrt_publish(StatusKind::Heartbeat, 0, "the studio beats again: playing");
        }
        return true;
    }
    const double quiet = std::chrono::duration<double>(now - beat_at_).count();
    if (quiet > give_up_) {
        status_.nrt_publish(
            StatusKind::Error, 0,
            "the studio's heartbeat stopped " + seconds_text(quiet) + " ago: the engine exits");
        return false;
    }
    if (!silenced_ && quiet > timeout_) {
        silenced_ = true;
        silent_.store(true);
        header_.engine_state.store(static_cast<std::uint32_t>(EngineState::Silent));
        status_.nrt_publish(StatusKind::Heartbeat, 0,
                            "silent: the studio's heartbeat stopped " + seconds_text(quiet) +
                                " ago; the sound comes back when it beats again");
    }
    return true;
}

}  // namespace archet
