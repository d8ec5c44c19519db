#pragma once
// The haptic device inside the real-time loop: before each simulation step a simulated hand
// (if that is the device) moves towards its target (the mouse pad or a gesture file) on the
// engine's clock, and on each haptic tick the gesture link exchanges positions and forces
// between the device and the model.

#include "archet/haptic_link.hpp"
#include "archet/simulated_hand.hpp"

namespace archet {

class HapticLoop {
  public:
    /// `simulation` gives the haptic level: the slowest level with gesture points. `hand` is
    /// the device itself when it is simulated, else null.
    HapticLoop(HapticDevice& device, SimulatedHand* hand, const Simulation& simulation);

    /// `target` moves a simulated hand; a real device ignores it (the player's hand is real).
    void before_step(Simulation& simulation, GestureSample target);

    const HapticLink& link() const { return link_; }

  private:
    SimulatedHand* hand_;
    HapticLink link_;
    int divider_ = 1;
    double period_ = 0;
};

}  // namespace archet
