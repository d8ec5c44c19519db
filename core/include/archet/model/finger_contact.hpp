#pragma once
// Where a finger at position p (0…1 along its n MATs) touches its string: between MAT
// `first` and MAT `first + 1`, at `weight` from the first (0 on it, 1 on the next). The
// model, its linear system and the simulation all place a finger with this one rule.

#include <algorithm>
#include <cstddef>

namespace archet {

struct FingerContact {
    std::size_t first = 0;
    double weight = 0;
};

inline FingerContact finger_contact(double position, std::size_t mats) {
    const double span = static_cast<double>(mats - 1);
    const double u = std::clamp(position, 0.0, 1.0) * span;
    const std::size_t first = std::min(static_cast<std::size_t>(u), mats - 2);
    return {first, u - static_cast<double>(first)};
}

}  // namespace archet
