#pragma once
// The real-time core process (`archet engine --shm NAME`). It attaches to the segment the
// studio created and runs two threads:
//  - control (this thread): validates and answers commands, loads and compiles models off the
//    real-time path, resolves parameter names, watches the studio's liveness, publishes status;
//  - real-time: the audio device's callback (or the null sink's clock), once per block: swaps
//    in a new model at a block boundary, applies parameter changes, steps the simulation,
//    writes the limited output and publishes probe and shape frames. It does not allocate,
//    lock, log or do I/O.

#include <string>

#include "archet/audio_output.hpp"

namespace archet {

struct EngineOptions {
    std::string segment;  ///< shared-memory name, from the studio
    AudioConfig audio;    ///< where the sound goes (null sink by default)
    int shape_every = 8;  ///< blocks between string-shape frames
    std::string haptic =
        "none";  ///< none: the pad sets the device position; sim: it moves a simulated hand
    /// The take directory (absolute): StartTake folders must lie inside it. Empty: no takes.
    std::string takes;
    /// The studio's pid, fixed at start (0: the segment header's, read once at attach; later
    /// writes to the header change nothing).
    int studio_pid = 0;
    double studio_timeout = 2;   ///< s without the studio's heartbeat: fade out, play nothing
    double studio_give_up = 60;  ///< s without it: exit
    /// mlockall the process (the engine's own); off when a test runs the engine in-process.
    bool lock_memory = true;
};

/// Runs until told to quit, the studio dies (SIGTERM from the kernel when it is the studio's
/// child, or its pidfd) or the studio's heartbeat stops for `studio_give_up`. Returns the exit
/// status (0 normal; 2 when the segment is missing or invalid).
int run_engine(const EngineOptions& options);

}  // namespace archet
