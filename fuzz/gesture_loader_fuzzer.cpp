// The gesture loader on arbitrary bytes. A gesture it accepts is sampled everywhere, then
// played (squeezed into 0.1 s, every keyframe kept) on the default bowed string: whatever the
// loader lets through must keep the simulation finite, or the sound would be NaN. What
// simdjson parses must read as nlohmann reads it (a byte-order mark sends it to nlohmann).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "archet/builders/bowed_string.hpp"
#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/physics/blow_up.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/simulation.hpp"
#include "parsers_agree.hpp"

namespace {

archet::Gesture squeezed(const archet::Gesture& gesture, double seconds) {
    std::vector<archet::GestureKeyframe> frames = gesture.keyframes();
    const double scale = gesture.duration() > 0 ? seconds / gesture.duration() : 1.0;
    for (auto& k : frames) k.time *= scale;
    return archet::Gesture(gesture.name(), std::move(frames));
}

const archet::CompiledModel* string = nullptr;

}  // namespace

// Built once, before fuzzing starts, so that the time it takes (seconds under the fuzzer's
// instrumentation) is not charged to the first input's -timeout. Without its stroke: the
// fuzzer plays its own gestures, and the band search would play 17 strokes of 3 s.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    archet::BowedStringOptions options;
    options.with_gesture = false;
    string = new archet::CompiledModel(archet::compile(archet::build_bowed_string(options)));
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    if (!parsers_agree(text, [](const std::string& t) {
            return archet::format_gesture(archet::parse_gesture(t, "fuzz"));
        }))
        __builtin_trap();
    try {
        const archet::Gesture gesture = archet::parse_gesture(text, "fuzz");
        for (double t = -1; t < gesture.duration() + 1; t += 0.01 + gesture.duration() / 64) {
            const archet::GestureSample s = gesture.at(t);
            if (!std::isfinite(s.slide) || !std::isfinite(s.press)) __builtin_trap();
        }
        const archet::Gesture played = squeezed(gesture, 0.1);
        archet::Simulation sim(*string);
        sim.set_gesture_track(&played);
        for (int i = 0; i < 4800; ++i) {
            sim.step();
            if (!std::isfinite(sim.output())) __builtin_trap();  // a non-finite sample
        }
        if (!archet::simulation_is_finite(sim)) __builtin_trap();
    } catch (const archet::InputError&) {
    }
    return 0;
}
