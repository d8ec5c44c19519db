#pragma once
// The gesture link at the haptic rate level: at each of its ticks, the device's newest
// positions go to the model's gesture points (scaled by their position_scale), and the mean
// force of the model on them (scaled by their force_scale) goes back to the device, clamped to
// what it can render and slew-limited. Stale device data gives zero force and holds the
// position. Real-time safe: no allocation, no I/O (a device with real I/O does it elsewhere).

#include <cstdint>

#include "archet/haptic_device.hpp"
#include "archet/physics/simulation.hpp"

namespace archet {

struct HapticLinkOptions {
    double stale_after = 0.01;  ///< s: older device data counts as stale
    double slew = 2000.0;       ///< N/s: fastest change of the rendered force
};

class HapticLink {
  public:
    HapticLink(HapticDevice& device, HapticLinkOptions options = {});

    /// One haptic tick at `time` (s); `period` is the haptic level's period.
    void tick(Simulation& simulation, double time, double period);

    std::uint64_t ticks() const { return ticks_; }
    std::uint64_t stale_ticks() const { return stale_; }
    std::uint64_t clamped_ticks() const { return clamped_; }
    GestureSample last_force() const { return sent_; }

  private:
    HapticDevice& device_;
    HapticLinkOptions options_;
    double max_force_;
    GestureSample sent_{};
    std::uint64_t ticks_ = 0, stale_ = 0, clamped_ = 0;
};

}  // namespace archet
