#pragma once
// A joystick through SDL2 (`--haptic sdl:INDEX`). Axis 0 slides the bow, axis 1 presses it.
// With force feedback, two constant-force effects (one per axis) are created once and only
// their levels are updated; a joystick without it plays with positions only and says so.
// Every SDL call happens on the device's own I/O thread, never the real-time one: it opens
// the joystick, reads the axes and sends the newest forces at the rate the device takes, and
// lets go of the stick when the simulation stops writing.

#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "archet/joystick_exchange.hpp"

namespace archet {

struct SdlOptions {
    double range = 0.05;          ///< m: a full deflection of an axis
    double max_force = 3.0;       ///< N at full effect level
    double update_rate = 500;     ///< Hz: how often axes are read and forces sent
    double write_timeout = 0.01;  ///< s without a new force before the device is let go
};

class SdlDevice final : public JoystickExchange {
  public:
    /// Opens joystick `index` (as `archet devices` lists them); throws InputError naming
    /// what is missing.
    explicit SdlDevice(int index, SdlOptions options = {});
    ~SdlDevice() override;
    SdlDevice(const SdlDevice&) = delete;
    SdlDevice& operator=(const SdlDevice&) = delete;

    HapticCapabilities capabilities() const override { return capabilities_; }
    /// Whether the joystick renders forces (else positions only).
    bool force_feedback() const { return capabilities_.max_force > 0; }

  private:
    struct Session;  // the SDL handles, owned by the I/O thread
    void io_loop_with(Session& session);

    SdlOptions options_;
    HapticCapabilities capabilities_;
    std::atomic<bool> running_{true};
    std::thread io_;
};

/// Each joystick SDL finds with two axes or more, by index, with or without force feedback.
std::vector<HapticDeviceInfo> list_sdl_joysticks();

}  // namespace archet
