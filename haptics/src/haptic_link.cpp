#include "archet/haptic_link.hpp"

#include <algorithm>
#include <cmath>

namespace archet {

HapticLink::HapticLink(HapticDevice& device, HapticLinkOptions options)
    : device_(device), options_(options), max_force_(device.capabilities().max_force) {}

void HapticLink::tick(Simulation& sim, double time, double period) {
    ++ticks_;
    const HapticReading r = device_.read();
    const bool stale = device_.stale(time, options_.stale_after);
    GestureSample wanted{};
    if (stale) {
        ++stale_;  // hold the last position, render nothing
    } else {
        sim.set_device_position({r.slide, r.press});
        wanted = sim.device_force();
    }
    auto shape = [&](double want, double previous) {
        double f = std::clamp(want, -max_force_, max_force_);
        if (f != want) ++clamped_;
        const double step = options_.slew * period;
        return stale ? 0.0 : std::clamp(f, previous - step, previous + step);
    };
    sent_ = {shape(wanted.slide, sent_.slide), shape(wanted.press, sent_.press)};
    device_.write(sent_.slide, sent_.press, time);
}

}  // namespace archet
