#pragma once
// The paper's sound examples, rendered offline: the shipped strings (110, 220, 440, 880 Hz)
// under the shipped gestures. `archet examples -o DIR`, the studio's "Render sound examples"
// and the Quick start without a display all render this one list.

#include <filesystem>
#include <string>
#include <vector>

namespace archet {

struct SoundExample {
    std::string file;     ///< WAV name in the output folder
    std::string model;    ///< under resources/models/
    std::string gesture;  ///< under resources/gestures/; empty: the model's own stroke
    std::string what;     ///< one line for the listener
};

const std::vector<SoundExample>& sound_examples();

/// Renders one example from `resources` into `folder` (created if needed); returns the path
/// written. Throws InputError naming a missing model or gesture.
std::filesystem::path render_sound_example(const SoundExample& example,
                                           const std::filesystem::path& resources,
                                           const std::filesystem::path& folder);

}  // namespace archet
