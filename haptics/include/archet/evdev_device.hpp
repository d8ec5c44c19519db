#pragma once
// A force-feedback joystick through Linux evdev (libevdev). Axis X slides the bow, axis Y
// presses it. Two constant-force effects are uploaded once; an I/O thread (never the
// real-time one) reads EV_ABS positions and updates the effects' levels with the newest force
// at the rate the device takes, and drops the force to zero when the simulation stops writing.

#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "archet/joystick_exchange.hpp"

struct libevdev;

namespace archet {

struct EvdevOptions {
    double range = 0.05;          ///< m: a full deflection of an axis
    double max_force = 3.0;       ///< N at full effect level
    double update_rate = 500;     ///< Hz: how often forces are sent (USB devices take 250–1000)
    double write_timeout = 0.01;  ///< s without a new force before the device is let go
};

class EvdevDevice final : public JoystickExchange {
  public:
    /// Opens `path` (/dev/input/eventN); throws InputError naming what is missing.
    explicit EvdevDevice(const std::string& path, EvdevOptions options = {});
    ~EvdevDevice() override;
    EvdevDevice(const EvdevDevice&) = delete;
    EvdevDevice& operator=(const EvdevDevice&) = delete;

    HapticCapabilities capabilities() const override { return capabilities_; }

  private:
    void io_loop();
    void send_levels(double slide, double press);

    std::string path_;
    EvdevOptions options_;
    HapticCapabilities capabilities_;
    int fd_ = -1;
    libevdev* device_ = nullptr;
    int effect_[2] = {-1, -1};
    int minimum_[2] = {0, 0}, maximum_[2] = {1, 1};
    std::atomic<bool> running_{false};
    std::thread io_;
};

/// Each readable input device with two absolute axes and constant-force effects, by path.
std::vector<HapticDeviceInfo> list_evdev_devices();

}  // namespace archet
