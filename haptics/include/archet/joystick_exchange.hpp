#pragma once
// What a real joystick's I/O thread and the real-time side share: the newest positions one
// way, the newest forces the other, and when each side last answered. Lock-free (atomics
// only), so the real-time side's read() and write() never wait for the device.

#include <atomic>

#include "archet/haptic_device.hpp"

namespace archet {

class JoystickExchange : public HapticDevice {
  public:
    HapticReading read() const override;
    void write(double slide_force, double press_force, double time) override;
    /// Positions arrive only when the stick moves, or are polled: the data is stale when the
    /// I/O thread stopped answering, not when the hand is still.
    bool stale(double time, double limit) const override;

  protected:
    // For the I/O thread:
    void publish_position(int axis, double metres);
    void answered();  ///< the device was just read
    /// The forces to send now: the newest ones, or zero when the simulation has not written
    /// for `timeout` seconds (it stalled).
    void forces_to_send(double timeout, double& slide, double& press) const;

  private:
    std::atomic<double> position_[2] = {0.0, 0.0};
    std::atomic<double> force_[2] = {0.0, 0.0};
    std::atomic<double> last_write_{-1.0};     ///< engine time of the last force written
    std::atomic<long long> last_write_ns_{0};  ///< monotonic time of it
    std::atomic<long long> last_poll_ns_{0};   ///< monotonic time the I/O thread last answered
};

}  // namespace archet
