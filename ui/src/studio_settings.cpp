#include "archet/ui/studio_settings.hpp"

#include <QFileInfo>
#include <QSettings>
#include <algorithm>

namespace archet::ui {

EngineClientOptions restore_engine_options(EngineClientOptions o) {
    QSettings s;
    s.beginGroup("engine");
    o.audio = s.value("audio", o.audio).toString();
    o.audio_device = s.value("audio_device", o.audio_device).toInt();
    o.buffer_frames = s.value("buffer_frames", o.buffer_frames).toInt();
    o.sample_rate = s.value("sample_rate", o.sample_rate).toDouble();
    o.haptic = s.value("haptic", o.haptic).toString();
    o.osc_port = std::clamp(s.value("osc_port", o.osc_port).toInt(), 0, 65535);
    o.midi = s.value("midi", o.midi).toString();
    o.midi_api = s.value("midi_api", o.midi_api).toString() == "jack" ? "jack" : "alsa";
    o.midi_map = s.value("midi_map", o.midi_map).toString();
    return o;
}

void save_engine_options(const EngineClientOptions& o) {
    QSettings s;
    s.beginGroup("engine");
    s.setValue("audio", o.audio);
    s.setValue("audio_device", o.audio_device);
    s.setValue("buffer_frames", o.buffer_frames);
    s.setValue("sample_rate", o.sample_rate);
    s.setValue("haptic", o.haptic);
    s.setValue("osc_port", o.osc_port);
    s.setValue("midi", o.midi);
    s.setValue("midi_api", o.midi_api);
    s.setValue("midi_map", o.midi_map);
}

QString last_model_path() {
    const QString path = QSettings().value("last_model").toString();
    return !path.isEmpty() && QFileInfo::exists(path) ? path : QString();
}

void save_last_model_path(const QString& path) {
    QSettings().setValue("last_model", path);
}

}  // namespace archet::ui
