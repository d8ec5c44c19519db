#include "audio_options.hpp"

#include "option_checks.hpp"

namespace archet::cli {

void add_audio_options(CLI::App& cmd, AudioConfig& c) {
    cmd.add_option("--audio", c.api,
                   "Audio output: jack, alsa, pulse, auto (the first of those that opens) or null")
        ->capture_default_str();
    cmd.add_option("--device", c.device,
                   "Device index of that API (-1: its default; see archet devices)")
        ->capture_default_str();
    cmd.add_option("--buffer", c.buffer_frames, "Frames per audio block")->capture_default_str();
    cmd.add_option("--rate", c.sample_rate, "Audio rate (Hz); the model runs at it")
        ->capture_default_str()
        ->check(sample_rate_range());
}

}  // namespace archet::cli
