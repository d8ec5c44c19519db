#include "archet/simulated_hand.hpp"

#include <cmath>

namespace archet {

SimulatedHand::SimulatedHand(SimulatedHandOptions options) : options_(options) {
    if (options_.force_timeout <= 0)
        options_.force_timeout = 1.0 / options_.capabilities.force_rate;
}

void SimulatedHand::write(double slide_force, double press_force, double time) {
    forces_.push(slide_force, press_force, time);
    last_force_write_ = time;
}

void SimulatedHand::advance(double time, double dt) {
    const auto& caps = options_.capabilities;
    // The device takes the newest force at its own rate, once the latency has passed, and lets
    // go when the simulation has stopped sending.
    if (time >= next_force_update_) {
        next_force_update_ = time + 1.0 / caps.force_rate;
        if (const auto* f = forces_.newest_before(time, options_.latency))
            applied_ = {f->slide, f->press};
    }
    if (last_force_write_ < 0 || time - last_force_write_ > options_.force_timeout)
        applied_ = {0, 0};
    // Hand and handle: m·a = grip·(target − x) − damping·v + rendered force (semi-implicit Euler).
    const double target[2] = {target_.slide, target_.press};
    const double force[2] = {applied_.slide, applied_.press};
    for (int a = 0; a < 2; ++a) {
        const double accel =
            (options_.grip * (target[a] - x_[a]) - options_.damping * v_[a] + force[a]) /
            options_.mass;
        v_[a] += accel * dt;
        x_[a] += v_[a] * dt;
        if (std::abs(x_[a]) > caps.range)
            x_[a] = std::copysign(caps.range, x_[a]), v_[a] = 0;  // end stops
    }
    // It measures at its own rate, quantised, and reports after the latency.
    if (time >= next_position_update_) {
        next_position_update_ = time + 1.0 / caps.position_rate;
        auto quantise = [&](double x) {
            return std::round(x / options_.resolution) * options_.resolution;
        };
        readings_.push(quantise(x_[0]), quantise(x_[1]), time);
        if (const auto* r = readings_.newest_before(time, options_.latency))
            reported_ = {r->slide, r->press, r->time};
    }
}

}  // namespace archet
