#pragma once
// What the studio remembers between runs (QSettings): the audio and device settings the
// engine was started with, and the model that was open last.

#include <QString>

#include "archet/ui/engine_client.hpp"

namespace archet::ui {

/// `defaults` with the audio output, buffer, rate, haptic device and OSC port saved last time.
EngineClientOptions restore_engine_options(EngineClientOptions defaults);
void save_engine_options(const EngineClientOptions& options);

/// The model file open when the studio last closed, if it still exists; empty otherwise.
QString last_model_path();
void save_last_model_path(const QString& path);

}  // namespace archet::ui
