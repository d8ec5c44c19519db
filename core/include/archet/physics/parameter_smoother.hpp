#pragma once
// Glides parameter changes made while a model plays, so that a new stiffness or friction
// coefficient arrives over a few milliseconds rather than as a step (a click). Fixed capacity,
// no allocation: safe on the real-time thread.

#include <array>
#include <cstddef>
#include <span>

#include "archet/physics/simulation.hpp"

namespace archet {

class ParameterSmoother {
  public:
    static constexpr std::size_t kCapacity = 32;

    /// Starts (or retargets) a glide of `slot` to `target` over `samples` steps. With no room
    /// left, the value is set at once.
    void glide(Simulation& sim, const ParameterSlot& slot, double target, int samples);
    /// Moves every glide one step; call once per simulation step.
    void advance(Simulation& sim);
    std::size_t active() const { return count_; }
    /// Forgets every glide (a new model).
    void clear() { count_ = 0; }

    struct Glide {
        ParameterSlot slot;
        double from = 0, to = 0;
        int done = 0, total = 1;  ///< steps made of its total
    };
    /// The glides under way, for a take that begins among them.
    std::span<const Glide> glides() const { return {glides_.data(), count_}; }
    /// Takes up a glide where it was (a take's re-render); false when there is no room.
    bool resume(const Glide& glide);

  private:
    std::array<Glide, kCapacity> glides_{};
    std::size_t count_ = 0;
};

}  // namespace archet
