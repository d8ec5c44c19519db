// The gesture loader on arbitrary bytes; a gesture it accepts is sampled everywhere.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "archet/input_error.hpp"
#include "archet/model_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const archet::Gesture gesture = archet::parse_gesture(text, "fuzz");
        for (double t = -1; t < gesture.duration() + 1; t += 0.01 + gesture.duration() / 64) {
            const archet::GestureSample s = gesture.at(t);
            if (!std::isfinite(s.slide) || !std::isfinite(s.press)) __builtin_trap();
        }
    } catch (const archet::InputError&) {
    }
    return 0;
}
