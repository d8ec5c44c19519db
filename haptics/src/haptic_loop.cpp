#include "archet/haptic_loop.hpp"

namespace archet {

HapticLoop::HapticLoop(HapticDevice& device, SimulatedHand* hand, const Simulation& sim)
    : hand_(hand), link_(device) {
    if (const CompiledLevel* hand = hand_level(sim.model()))
        divider_ = hand->divider, period_ = hand->dt;
    else
        period_ = 1.0 / sim.sample_rate();
}

void HapticLoop::before_step(Simulation& sim, GestureSample target, double device_time) {
    between_link_ticks(target, device_time, 1.0 / sim.sample_rate());
    if (sim.tick() % static_cast<std::uint64_t>(divider_) == 0)
        link_.tick(sim, device_time, period_);
}

void HapticLoop::between_link_ticks(GestureSample target, double device_time, double dt) {
    if (!hand_) return;
    hand_->set_target(target);
    hand_->advance(device_time, dt);
}

}  // namespace archet
