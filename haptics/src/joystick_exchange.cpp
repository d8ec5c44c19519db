#include "archet/joystick_exchange.hpp"

#include "archet/common/monotonic_clock.hpp"

namespace archet {

HapticReading JoystickExchange::read() const {
    return {position_[0].load(std::memory_order_relaxed),
            position_[1].load(std::memory_order_relaxed),
            last_write_.load(std::memory_order_relaxed)};
}

void JoystickExchange::write(double slide, double press, double time) {
    force_[0].store(slide, std::memory_order_relaxed);
    force_[1].store(press, std::memory_order_relaxed);
    last_write_.store(time, std::memory_order_relaxed);
    last_write_ns_.store(monotonic_ns(), std::memory_order_relaxed);
}

bool JoystickExchange::stale(double, double limit) const {
    const long long since = monotonic_ns() - last_poll_ns_.load(std::memory_order_relaxed);
    return static_cast<double>(since) * 1e-9 > limit;
}

void JoystickExchange::publish_position(int axis, double metres) {
    position_[axis].store(metres, std::memory_order_relaxed);
}

void JoystickExchange::answered() {
    last_poll_ns_.store(monotonic_ns(), std::memory_order_relaxed);
}

void JoystickExchange::forces_to_send(double timeout, double& slide, double& press) const {
    const long long since = monotonic_ns() - last_write_ns_.load(std::memory_order_relaxed);
    const bool stalled = static_cast<double>(since) * 1e-9 > timeout;
    slide = stalled ? 0.0 : force_[0].load(std::memory_order_relaxed);
    press = stalled ? 0.0 : force_[1].load(std::memory_order_relaxed);
}

}  // namespace archet
