#include "archet/model/gesture_validation.hpp"

#include <cmath>

#include "archet/common/input_limits.hpp"
#include "archet/common/number_text.hpp"
#include "archet/model/model_parameters.hpp"

namespace archet {

namespace {

// The two axes, checked by the parameter table's own range message ("press must be at most
// 1 m (is 1e+308)").
const ParameterInfo kSlide{"slide", "m", -limits::kPosition, false, limits::kPosition};
const ParameterInfo kPress{"press", "m", -limits::kPress, false, limits::kPress};

}  // namespace

std::optional<InputError> check_gesture(const Gesture& gesture, const std::string& source) {
    const auto& frames = gesture.keyframes();
    if (frames.empty()) return InputError(source, "a gesture needs at least one keyframe");
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const GestureKeyframe& k = frames[i];
        const std::string where = source + " keyframe #" + std::to_string(i + 1);
        if (!std::isfinite(k.time) || !std::isfinite(k.slide) || !std::isfinite(k.press))
            return InputError(where, "t, slide and press must be finite numbers");
        if (i == 0 && k.time < 0.0) return InputError(where, "time must not be negative");
        if (i > 0 && !(k.time > frames[i - 1].time))
            return InputError(where, "times must increase strictly (t = " + format_number(k.time) +
                                         " s follows t = " + format_number(frames[i - 1].time) +
                                         " s)");
        if (k.time > limits::kDurationSeconds)
            return InputError(where, "t = " + format_number(k.time) + " s is beyond " +
                                         format_number(limits::kDurationSeconds) +
                                         " s, the longest gesture Archet plays; split the piece");
        for (const std::string& problem :
             {range_problem(kSlide, k.slide), range_problem(kPress, k.press)})
            if (!problem.empty()) return InputError(where, problem);
    }
    return std::nullopt;
}

}  // namespace archet
