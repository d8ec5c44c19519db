#pragma once
// The haptic device inside the real-time loop: before each simulation step a simulated hand
// (if that is the device) moves towards its target (the mouse pad or a gesture file) on the
// engine's clock, and on each haptic tick the gesture link exchanges positions and forces
// between the device and the model.

#include <cstdint>

#include "archet/haptic_link.hpp"
#include "archet/simulated_hand.hpp"

namespace archet {

class HapticLoop {
  public:
    /// `simulation` gives the haptic level: the slowest level with gesture points. `hand` is
    /// the device itself when it is simulated, else null.
    HapticLoop(HapticDevice& device, SimulatedHand* hand, const Simulation& simulation);

    /// `target` moves a simulated hand; a real device ignores it (the player's hand is real).
    /// `device_time` (s) is the device's own clock: it runs on when the engine swaps in a new
    /// model, whose own time starts again at 0. A device judged on model time would wait for
    /// the old model's time to come round again before it reported a new position.
    void before_step(Simulation& simulation, GestureSample target, double device_time);
    /// What before_step() does at a tick where the link does not tick: a simulated hand moves
    /// on. It reads nothing of the simulation, so the engine may call it for the ticks of a
    /// run ahead of running them.
    void between_link_ticks(GestureSample target, double device_time, double dt);
    /// Ticks of the master clock from `tick` to the link's next tick (1 … its divider).
    std::uint64_t ticks_to_link_tick(std::uint64_t tick) const {
        const auto divider = static_cast<std::uint64_t>(divider_);
        return divider - tick % divider;
    }

    const HapticLink& link() const { return link_; }

  private:
    SimulatedHand* hand_;
    HapticLink link_;
    int divider_ = 1;
    double period_ = 0;
};

}  // namespace archet
