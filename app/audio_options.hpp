#pragma once
// The audio-output options shared by the commands that play live.

#include <CLI/CLI.hpp>

#include "archet/audio_output.hpp"

namespace archet::cli {

void add_audio_options(CLI::App& command, AudioConfig& config);

}  // namespace archet::cli
