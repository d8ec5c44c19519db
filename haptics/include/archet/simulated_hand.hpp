#pragma once
// A hand on a simulated device, for tests and for the studio's mouse pad: per axis a mass
// with damping, gripping a target (mouse or gesture file) through a spring, pushed by the
// forces the model feeds back. The device reports positions and takes forces only at its own
// rates, after a latency, with a position resolution, and drops the force to zero when no new
// force arrives in time (a stalled simulation). Deterministic: it advances on the engine's
// clock, not the wall's.

#include <algorithm>
#include <array>

#include "archet/haptic_device.hpp"
#include "archet/model/gesture.hpp"

namespace archet {

struct SimulatedHandOptions {
    double mass = 0.5;         ///< kg per axis: hand and handle
    double damping = 25.0;     ///< N·s/m: the arm's own damping (about critical with grip)
    double grip = 300.0;       ///< N/m: how firmly the hand follows its target
    double latency = 0.001;    ///< s before a reading is reported and a force applied
    double resolution = 1e-5;  ///< m, position quantisation
    double force_timeout =
        0.0;  ///< s without a new force before it drops to 0 (0: one device period)
    HapticCapabilities capabilities{"simulated hand", 0.1, 5.0, 1000, 1000};
};

class SimulatedHand final : public HapticDevice {
  public:
    explicit SimulatedHand(SimulatedHandOptions options = {});

    /// Where the hand wants the handle to be (a mouse, or a gesture file).
    void set_target(GestureSample target) { target_ = target; }
    /// Advances the hand by dt on the engine's clock (call it every master tick or so).
    void advance(double time, double dt);

    HapticCapabilities capabilities() const override { return options_.capabilities; }
    HapticReading read() const override { return reported_; }
    void write(double slide_force, double press_force, double time) override;

    /// The force the device is rendering now (after latency, rate and timeout).
    GestureSample applied_force() const { return applied_; }
    GestureSample position() const { return {x_[0], x_[1]}; }

  private:
    // What was sent or measured, kept until it is old enough to arrive: a fixed ring, newest last.
    struct Delayed {
        struct Entry {
            double slide = 0, press = 0, time = -1;
        };
        std::array<Entry, 256> entries{};
        std::size_t next = 0;
        void push(double slide, double press, double time) {
            entries[next % entries.size()] = {slide, press, time};
            ++next;
        }
        /// The newest entry at least `delay` old at `now`, or none.
        const Entry* newest_before(double now, double delay) const {
            for (std::size_t k = 0; k < std::min(next, entries.size()); ++k) {
                const Entry& e = entries[(next - 1 - k) % entries.size()];
                if (e.time <= now - delay + 1e-12) return &e;
            }
            return nullptr;
        }
    };
    SimulatedHandOptions options_;
    GestureSample target_{};
    double x_[2] = {0, 0}, v_[2] = {0, 0};
    HapticReading reported_;
    GestureSample applied_{};
    Delayed forces_;    ///< written by the link
    Delayed readings_;  ///< measured by the device
    double last_force_write_ = -1;
    double next_position_update_ = 0, next_force_update_ = 0;
};

}  // namespace archet
