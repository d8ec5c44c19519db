#pragma once
// A simulated hand on the device inside the real-time loop: before each simulation step the
// hand moves towards its target (the mouse pad or a gesture file) on the engine's clock, and
// on each haptic tick the gesture link exchanges positions and forces with the model.

#include "archet/haptic_link.hpp"
#include "archet/simulated_hand.hpp"

namespace archet {

class HandLoop {
  public:
    /// `simulation` gives the haptic level: the slowest level with gesture points.
    HandLoop(SimulatedHand& hand, const Simulation& simulation);

    void before_step(Simulation& simulation, GestureSample target);

    const HapticLink& link() const { return link_; }
    int haptic_divider() const { return divider_; }
    double haptic_period() const { return period_; }

  private:
    SimulatedHand& hand_;
    HapticLink link_;
    int divider_ = 1;
    double period_ = 0;
};

}  // namespace archet
