#include "archet/gesture_validation.hpp"

#include <cmath>

#include "archet/input_limits.hpp"
#include "archet/number_text.hpp"

namespace archet {

namespace {

// "press must be at most 1 m (is 1e+308)", or "" when |value| <= bound.
std::string outside(const char* name, double value, double bound) {
    if (value >= -bound && value <= bound) return {};
    return std::string(name) + " must be " +
           (value > 0 ? "at most " + format_number(bound) : "at least " + format_number(-bound)) +
           " m (is " + format_number(value) + ")";
}

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
        for (const std::string& problem : {outside("slide", k.slide, limits::kPosition),
                                           outside("press", k.press, limits::kPress)})
            if (!problem.empty()) return InputError(where, problem);
    }
    return std::nullopt;
}

}  // namespace archet
