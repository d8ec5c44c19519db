#pragma once
// A model as the real-time thread runs it. The control thread builds it (compiles, checks its
// cost) and hands it over through ThreadBridge::pending; from then on the real-time thread
// owns it until it hands it back through ThreadBridge::retired for the control thread to
// delete. Only the control thread allocates or frees one.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "archet/haptic_choice.hpp"
#include "archet/haptic_loop.hpp"
#include "archet/model/model.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/simulation.hpp"

namespace archet {

struct LoadedModel {
    CompiledModel resolver;  ///< names → slots, on the control thread
    std::unique_ptr<Simulation> simulation;
    /// The string's MATs the studio draws (drawn_points() of string_points), in model order.
    std::vector<MatSlot> shape;
    std::uint32_t shape_spread_over = 0;  ///< how many string points those are drawn from
    std::optional<HapticLoop> haptic;     ///< with a device: its loop and link for this model
    std::uint64_t haptic_divider = 1;     ///< the gesture points' level, for takes
    double haptic_dt = 0;
    bool has_energy_probe = false;  ///< any probe of kind Energy
    std::size_t energy_probe = 0;   ///< the first of them, when there is one
    double held_energy = 0;         ///< J, the last stored energy the scopes were given
    std::uint64_t generation = 0;   ///< which load of the control thread it comes from
    std::uint32_t sequence = 0;
    /// The playing model with its bow moved: it takes over that model's motion (the state,
    /// through `handover`, sized here) instead of starting from rest and cross-fading.
    bool continues = false;
    std::vector<double> handover;
    /// A take recording on keeps the move: "bow.position" under this name in its changes.
    bool bow_move_named = false;
    std::uint32_t bow_move_name = 0;
    double bow_position = 0;
};

/// Control thread: compiles a validated model at the device's rate into what the real-time
/// thread runs; `sequence` is the load command it answers, `generation` the load it counts as.
/// Its bowed chain loop runs in `build`, else in the one fastest_chain_build() times (the same
/// model again, or with its bow moved, keeps the build it was timed to).
std::unique_ptr<LoadedModel> nrt_prepare_model(const Model& model, double sample_rate,
                                               const HapticChoice& haptic, std::uint32_t sequence,
                                               std::uint64_t generation,
                                               std::optional<ChainBuild> build = std::nullopt);

/// Control thread: throws an InputError naming `path` when stepping the model takes more than
/// its share of the device's time per sample (it would xrun on every block of `block_frames`).
void nrt_check_cost(const std::string& path, const LoadedModel& loaded, double sample_rate,
                    int block_frames);

}  // namespace archet
