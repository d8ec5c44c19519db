#pragma once
// SIGINT, SIGTERM and SIGHUP as requests to stop, for the commands that can stop cleanly
// (`play`, `render`, `engine`). While an InterruptionGuard lives, the first of these signals
// only sets a flag (async-signal-safe); the command's loop polls interruption_signal(),
// finishes its take or removes its temporary files, and the command exits with 128 + the
// signal's number: 130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP. A second signal of the
// same kind has its default effect and ends the process at once.

#include <stdexcept>
#include <string>

namespace archet {

class InterruptionGuard {
  public:
    /// Installs the handlers; the flag starts clear. `second_ends_at_once`: a second signal of
    /// the same kind has its default effect (a command the user wants gone); the engine keeps
    /// its handler, since the studio's death signal and a terminal's may both come, and it
    /// must still remove the segment.
    explicit InterruptionGuard(bool second_ends_at_once = true);
    ~InterruptionGuard();  ///< puts the previous handlers back
    InterruptionGuard(const InterruptionGuard&) = delete;
    InterruptionGuard& operator=(const InterruptionGuard&) = delete;
};

/// The first signal received while a guard lived, or 0.
int interruption_signal();
/// "SIGINT", "SIGTERM", "SIGHUP" (or "signal N").
std::string signal_name(int signal);

/// What a command throws when a signal stops it; main() prints it and exits with status().
class Interrupted : public std::runtime_error {
  public:
    Interrupted(int signal, const std::string& what);
    int signal() const { return signal_; }
    int status() const { return 128 + signal_; }

  private:
    int signal_;
};

/// Throws Interrupted, saying `what` was left undone, if a signal arrived.
void throw_if_interrupted(const std::string& what);

}  // namespace archet
