#pragma once
// Where the engine plays: the audio output (an API's default or one of its devices) and its buffer,
// what holds the bow (the pad's simulated hand, the pad directly, or a joystick found through
// evdev or SDL), and what else plays it: OSC, MIDI (a source and a mapping file, checked before
// it is taken). Applying it restarts the engine with the same model.

#include <QDialog>

#include "archet/ui/engine_client.hpp"

class QComboBox;
class QLabel;
class QLineEdit;
class QSpinBox;

namespace archet::ui {

class SettingsDialog : public QDialog {
    Q_OBJECT

  public:
    SettingsDialog(const EngineClientOptions& current, QWidget* parent = nullptr);
    EngineClientOptions options() const;

    /// The audio choices' item role holding the device index (the api is the item's data).
    static constexpr int kDeviceRole = Qt::UserRole + 1;

    /// The MIDI choices' item role holding the API (the source is the item's data).
    static constexpr int kMidiApiRole = Qt::UserRole + 2;

    void accept() override;  ///< refuses a mapping file that does not read, saying why

  private:
    void add_audio_choices(const EngineClientOptions& current);
    void add_midi_choices(const EngineClientOptions& current);
    QWidget* midi_map_row();

    EngineClientOptions current_;
    QComboBox* audio_;
    QSpinBox* buffer_;
    QSpinBox* osc_;
    QComboBox* rate_;
    QComboBox* haptic_;
    QComboBox* midi_;
    QLineEdit* midi_map_;
    QLabel* midi_map_problem_;
};

}  // namespace archet::ui
