#pragma once
// A 2-axis force-feedback device as the engine sees it: positions in, forces out, and what
// it can do. Axis 0 slides the bow, axis 1 presses it.

#include <string>

namespace archet {

struct HapticCapabilities {
    std::string name;
    double range = 0.1;           ///< m, travel either side of centre, per axis
    double max_force = 5.0;       ///< N, per axis
    double position_rate = 1000;  ///< Hz, how often it reports positions
    double force_rate = 1000;     ///< Hz, how often it takes new forces
};

/// A device Archet can play with, as `archet devices` and the studio's settings list it.
struct HapticDeviceInfo {
    std::string backend;  ///< evdev, sdl or sim
    std::string address;  ///< /dev/input/eventN for evdev, the joystick index for sdl; sim: ""
    std::string name;     ///< the device's own name
    int axes = 0;         ///< absolute axes it reports (two are used)
    bool force_feedback = false;

    /// What --haptic takes: evdev:/dev/input/eventN, sdl:N, sim.
    std::string id() const { return address.empty() ? backend : backend + ":" + address; }
};

struct HapticReading {
    double slide = 0, press = 0;  ///< m
    double time = -1;             ///< s on the engine's clock when measured; < 0: never
};

class HapticDevice {
  public:
    virtual ~HapticDevice() = default;
    virtual HapticCapabilities capabilities() const = 0;
    /// The newest positions the device has reported.
    virtual HapticReading read() const = 0;
    /// The forces to render (N); the device takes the newest at its own rate.
    virtual void write(double slide_force, double press_force, double time) = 0;
    /// Whether its data is too old to trust at engine time `time`. By default from the reading's
    /// time; a device that reports only changes judges by when it last answered at all.
    virtual bool stale(double time, double limit) const {
        const HapticReading r = read();
        return r.time < 0 || time - r.time > limit;
    }
};

}  // namespace archet
