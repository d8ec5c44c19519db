#pragma once
// Offline rendering: steps a simulation for a number of master ticks and hands the audio
// output and the probe values to a sink block by block. No file I/O here (see audio/).

#include <cstdint>
#include <functional>
#include <vector>

#include "archet/physics/simulation.hpp"

namespace archet {

struct RenderBlock {
    std::uint64_t first_frame = 0;  ///< frames rendered before this block (not the model's tick)
    std::size_t frames = 0;
    const double* audio = nullptr;   ///< frames values
    const double* probes = nullptr;  ///< frames × probe_count values, row by row (or null)
    std::size_t probe_count = 0;
};

struct RenderOptions {
    std::uint64_t frames = 0;
    bool with_probes = false;
    std::size_t block_frames = 4096;
    /// Called before every step when set (e.g. to replay a take's parameter changes).
    std::function<void(Simulation&)> before_step;
};

/// Steps `simulation` options.frames times, calling `sink` after each block. A render of 48,000
/// frames or more without a before_step runs in the build of the bowed chain's loop that
/// fastest_chain_build() finds, and `simulation` keeps it. Denormals are flushed to zero while it
/// runs (see DenormalGuard). Throws InputError, before the block is handed on, when an output
/// sample, a probe or a position stops being finite (blow_up.hpp).
void render(Simulation& simulation, const RenderOptions& options,
            const std::function<void(const RenderBlock&)>& sink);

}  // namespace archet
