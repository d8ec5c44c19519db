#pragma once
// Where the engine plays: the audio output (an API's default or one of its devices) and its buffer,
// and what holds the bow (the pad's simulated hand, the pad directly, or a joystick found through
// evdev or SDL). Applying it restarts the engine with the same model.

#include <QDialog>

#include "archet/ui/engine_client.hpp"

class QComboBox;
class QSpinBox;

namespace archet::ui {

class SettingsDialog : public QDialog {
    Q_OBJECT

  public:
    SettingsDialog(const EngineClientOptions& current, QWidget* parent = nullptr);
    EngineClientOptions options() const;

    /// The audio choices' item role holding the device index (the api is the item's data).
    static constexpr int kDeviceRole = Qt::UserRole + 1;

  private:
    void add_audio_choices(const EngineClientOptions& current);

    EngineClientOptions current_;
    QComboBox* audio_;
    QSpinBox* buffer_;
    QSpinBox* osc_;
    QComboBox* rate_;
    QComboBox* haptic_;
};

}  // namespace archet::ui
