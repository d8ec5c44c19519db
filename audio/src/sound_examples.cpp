#include "archet/sound_examples.hpp"

#include "archet/common/input_error.hpp"

#include <cmath>

#include "archet/files/model_file.hpp"
#include "archet/interruption.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/renderer.hpp"
#include "archet/sound_file_writer.hpp"

namespace archet {

const std::vector<SoundExample>& sound_examples() {
    static const std::vector<SoundExample> examples{
        {"sound-1-110Hz-steady-bow.wav", "bowed-string-110.json", "",
         "110 Hz full-bandwidth string with the violin body, the steady stroke it carries"},
        {"sound-2-110Hz-harmonic-steady-bow.wav", "bowed-string-110-harmonic.json", "",
         "its harmonic retuning, the stroke it carries"},
        {"sound-3-220Hz-detache.wav", "bowed-string-220.json", "detache.json",
         "220 Hz, détaché strokes"},
        {"sound-4-220Hz-harmonic-crescendo.wav", "bowed-string-220-harmonic.json", "crescendo.json",
         "220 Hz harmonic string, a crescendo of bow force"},
        {"sound-5-440Hz-crescendo.wav", "bowed-string-440.json", "crescendo.json",
         "440 Hz, a crescendo"},
        {"sound-6-440Hz-harmonic-steady-bow.wav", "bowed-string-440-harmonic.json", "",
         "440 Hz harmonic string, the steady stroke it carries"},
        {"sound-7-880Hz-pressure-sweep.wav", "bowed-string-880.json", "pressure-sweep.json",
         "880 Hz, bow force swept through Schelleng's playable band"},
        {"sound-8-880Hz-steady-bow.wav", "bowed-string-880.json", "",
         "880 Hz, the steady stroke it carries"},
        {"sound-9-110Hz-paper-steady-bow.wav", "bowed-string-110-paper.json", "steady-bow.json",
         "the paper's 110 Hz chaplet, the shipped steady stroke: the slow attack of a homogeneous "
         "chain, and nothing above 4.4 kHz"},
        {"sound-10-110Hz-paper-harmonic-steady-bow.wav", "bowed-string-110-harmonic-paper.json",
         "steady-bow.json", "the same stroke on its harmonic retuning: Helmholtz motion sooner"},
    };
    return examples;
}

std::filesystem::path render_sound_example(const SoundExample& example,
                                           const std::filesystem::path& resources,
                                           const std::filesystem::path& folder) {
    const Model model = load_model_file(resources / "models" / example.model);
    validate_model(model);
    if (example.gesture.empty() && !model.gesture)
        throw InputError(example.model, "carries no stroke; give the example a gesture");
    const Gesture gesture = example.gesture.empty()
                                ? *model.gesture
                                : load_gesture_file(resources / "gestures" / example.gesture);
    std::error_code ec;
    if (std::filesystem::exists(folder, ec) && !std::filesystem::is_directory(folder, ec))
        throw InputError(folder.string(),
                         "is a file, not a folder; give a folder for the sound "
                         "examples (it is created if missing)");
    std::filesystem::create_directories(folder, ec);
    if (ec)
        throw InputError(folder.string(), "cannot create the folder: " + ec.message() +
                                              " (is its parent writable?)");
    Simulation sim(compile(model));
    sim.set_gesture_track(&gesture);
    const std::filesystem::path path = folder / example.file;
    SoundFileWriter wav(path, SoundFormat::Wav, static_cast<int>(std::lround(sim.sample_rate())));
    RenderOptions options;
    options.frames =
        static_cast<std::uint64_t>(std::llround((gesture.duration() + 0.5) * sim.sample_rate()));
    render(sim, options, [&](const RenderBlock& b) {
        // Under an InterruptionGuard (`archet examples`), a signal stops it: no temporary left.
        throw_if_interrupted(path.string() + " not written");
        wav.write(b.audio, b.frames);
    });
    wav.close();
    return path;
}

}  // namespace archet
