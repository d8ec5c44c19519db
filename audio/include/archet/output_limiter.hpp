#pragma once
// Keeps live output within full scale: a peak limiter with instant attack and a slow release,
// so a loud transient is turned down rather than clipped, and a non-finite sample mutes.
// Real-time safe: a few multiplications per sample.

#include <cmath>

namespace archet {

class OutputLimiter {
  public:
    explicit OutputLimiter(double sample_rate, double ceiling = 0.98, double release_seconds = 0.2)
        : ceiling_(ceiling), release_(std::exp(-1.0 / (release_seconds * sample_rate))) {}

    /// The limited sample; NaN or infinity gives silence and counts.
    float process(double x) {
        if (!std::isfinite(x)) {
            ++non_finite_;
            return 0.0f;
        }
        envelope_ = std::max(std::abs(x), envelope_ * release_);
        const double gain = envelope_ > ceiling_ ? ceiling_ / envelope_ : 1.0;
        if (gain < 1.0) ++limited_;
        return static_cast<float>(x * gain);
    }

    unsigned long long limited() const { return limited_; }
    unsigned long long non_finite() const { return non_finite_; }

  private:
    double ceiling_, release_, envelope_ = 0;
    unsigned long long limited_ = 0, non_finite_ = 0;
};

}  // namespace archet
