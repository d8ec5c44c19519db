#pragma once
// The real-time core process (`archet engine --shm NAME`). It attaches to the segment the
// studio created and runs two threads:
//  - control (ControlThread, this thread, non-real-time): validates and answers commands,
//    loads and compiles models off the real-time path, resolves parameter names, watches the
//    studio's liveness (StudioWatch), publishes status (StatusPublisher), finishes takes and
//    deletes retired models;
//  - real-time (RealtimeThread): the audio device's callback (or the null sink's clock), once
//    per block: swaps in a new model at a block boundary, applies parameter changes, steps the
//    simulation, writes the limited output and publishes probe and shape frames. It does not
//    allocate, lock, log or do I/O.
// They share only ThreadBridge (atomics and local lock-free rings) and the LoadedModels passed
// through it.

#include "archet/engine/engine_options.hpp"

namespace archet {

/// Runs until told to quit, the studio dies (SIGTERM from the kernel when it is the studio's
/// child, or its pidfd) or the studio's heartbeat stops for `studio_give_up`. Returns the exit
/// status (0 normal; 2 when the segment is missing or invalid).
int run_engine(const EngineOptions& options);

}  // namespace archet
