#pragma once
// The real-time core process (`archet engine --shm NAME`). It attaches to the segment the
// studio created and runs two threads:
//  - control (this thread): validates and answers commands, loads and compiles models off the
//    real-time path, resolves parameter names, watches the studio's liveness, publishes status;
//  - real-time: wakes at absolute block deadlines of the master clock (a null sink clocked in
//    real time; audio devices come next), swaps in a new model at a block boundary, applies
//    parameter changes, steps the simulation and publishes probe and shape frames. It does not
//    allocate, lock, log or do I/O.

#include <string>

namespace archet {

struct EngineOptions {
    std::string segment;    ///< shared-memory name, from the studio
    int block_frames = 64;  ///< frames per real-time block
    int shape_every = 8;    ///< blocks between string-shape frames
};

/// Runs until told to quit or the studio dies. Returns the exit status (0 normal; 2 when the
/// segment is missing or invalid).
int run_engine(const EngineOptions& options);

}  // namespace archet
