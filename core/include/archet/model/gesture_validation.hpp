#pragma once
// One check for every gesture, whether it comes from a gesture file, a model's embedded
// gesture or a take: keyframes in time order, within an hour, and every position within the
// physical ranges of input_limits.hpp.

#include <optional>
#include <string>

#include "archet/common/input_error.hpp"
#include "archet/model/gesture.hpp"

namespace archet {

/// The first problem of `gesture`, named "SOURCE keyframe #N", or nothing.
std::optional<InputError> check_gesture(const Gesture& gesture, const std::string& source);

}  // namespace archet
