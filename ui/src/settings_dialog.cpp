#include "archet/ui/settings_dialog.hpp"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>

#include "archet/audio_output.hpp"
#include "archet/haptic_choice.hpp"
#include "archet/midi/midi_mapping.hpp"
#include "archet/midi_ports.hpp"

namespace archet::ui {

SettingsDialog::SettingsDialog(const EngineClientOptions& current, QWidget* parent)
    : QDialog(parent), current_(current) {
    setWindowTitle(tr("Audio and devices"));
    audio_ = new QComboBox;
    audio_->setObjectName("audio");
    add_audio_choices(current);
    buffer_ = new QSpinBox;
    buffer_->setRange(16, 4096);
    buffer_->setSuffix(tr(" frames"));
    buffer_->setValue(current.buffer_frames);
    rate_ = new QComboBox;
    for (const double hz : {44100.0, 48000.0, 88200.0, 96000.0})
        rate_->addItem(tr("%1 kHz").arg(hz / 1000, 0, 'g', 4), hz);
    rate_->setCurrentIndex(std::max(0, rate_->findData(current.sample_rate)));
    rate_->setToolTip(
        tr("Asked of the device; the model runs at the rate the device gives "
           "(the status bar says which)"));
    haptic_ = new QComboBox;
    haptic_->setObjectName("haptic");
    // The devices found now, under the ids --haptic takes: the simulated hand first, in the
    // studio's words, then no device, then the joysticks as `archet devices` lists them.
    for (const HapticDeviceInfo& d : list_haptic_choices()) {
        const bool sim = d.backend == "sim";
        haptic_->insertItem(
            sim ? 0 : haptic_->count(),
            sim ? tr("The pad moves a simulated hand") : QString::fromStdString(describe(d)),
            QString::fromStdString(d.id()));
    }
    haptic_->insertItem(1, tr("The pad sets the bow's position directly"), "none");
    haptic_->setCurrentIndex(std::max(0, haptic_->findData(current.haptic)));
    osc_ = new QSpinBox;
    osc_->setObjectName("osc");
    osc_->setRange(0, 65535);
    osc_->setSpecialValueText(tr("off"));
    osc_->setValue(current.osc_port);
    osc_->setToolTip(
        tr("The UDP port the engine listens on for OSC from this machine's programs "
           "(/archet/bow/slide, /archet/bow/press, /archet/finger, /archet/param, "
           "/archet/record; see the user guide)"));
    midi_ = new QComboBox;
    midi_->setObjectName("midi");
    add_midi_choices(current);
    midi_->setToolTip(
        tr("Notes stop the string with the model's finger and bow it; controllers set the bow's "
           "force and speed, vibrato and any parameter (Play → MIDI learn…)"));
    auto* note =
        new QLabel(tr("Each axis's displacement and force scaling are the gesture "
                      "points' position_scale and force_scale: select a hand in the "
                      "graph and edit them in the inspector, live."));
    note->setWordWrap(true);
    auto* form = new QFormLayout(this);
    form->addRow(tr("Audio output"), audio_);
    form->addRow(tr("Buffer"), buffer_);
    form->addRow(tr("Sample rate"), rate_);
    form->addRow(tr("Bow held by"), haptic_);
    form->addRow(tr("OSC port"), osc_);
    form->addRow(tr("MIDI input"), midi_);
    form->addRow(tr("MIDI map"), midi_map_row());
    form->addRow(midi_map_problem_);
    form->addRow(note);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    form->addRow(buttons);
}

// Each API's default output, then every output device the APIs list now, each carrying what
// the engine's --audio and --device take.
void SettingsDialog::add_audio_choices(const EngineClientOptions& current) {
    int chosen = -1;
    auto add = [&](const QString& label, const QString& api, int device) {
        audio_->addItem(label, api);
        audio_->setItemData(audio_->count() - 1, device, kDeviceRole);
        if (api == current.audio && device == current.audio_device) chosen = audio_->count() - 1;
    };
    add(tr("First that opens (JACK, PulseAudio, ALSA)"), "auto", -1);
    add(tr("JACK"), "jack", -1);
    add(tr("PulseAudio"), "pulse", -1);
    add(tr("ALSA"), "alsa", -1);
    add(tr("None (a silent clock)"), "null", -1);
    for (const AudioApiDevices& api : list_audio_devices())
        for (const AudioDeviceInfo& d : api.devices)
            if (d.api != "null")  // the silent clock is offered above
                add(QString::fromStdString(describe(d)), QString::fromStdString(d.api), d.index);
    // A device that is gone: its API's default output.
    audio_->setCurrentIndex(chosen >= 0 ? chosen : std::max(0, audio_->findData(current.audio)));
}

// Off, the engine's own port for either API (others connect to it), then every source the APIs
// list now; a source chosen before and gone now stays, said to be missing.
void SettingsDialog::add_midi_choices(const EngineClientOptions& current) {
    auto add = [&](const QString& label, const QString& source, const QString& api) {
        midi_->addItem(label, source);
        midi_->setItemData(midi_->count() - 1, api, kMidiApiRole);
        if (source == current.midi && (source.isEmpty() || api == current.midi_api))
            midi_->setCurrentIndex(midi_->count() - 1);
    };
    add(tr("Off"), "", "alsa");
    add(tr("Archet's own port, archet-midi:midi_in (ALSA sequencer)"), "virtual", "alsa");
    add(tr("Archet's own port, archet-midi:midi_in (JACK)"), "virtual", "jack");
    bool found = current.midi.isEmpty() || current.midi == "virtual";
    for (const std::string& api : midi_apis())
        for (const std::string& port : list_midi_inputs(api)) {
            const QString name = QString::fromStdString(port);
            found =
                found || (name == current.midi && QString::fromStdString(api) == current.midi_api);
            add(QString::fromStdString(api == "jack" ? "JACK: " : "ALSA: ") + name, name,
                QString::fromStdString(api));
        }
    if (!found) add(tr("%1 (not found now)").arg(current.midi), current.midi, current.midi_api);
}

QWidget* SettingsDialog::midi_map_row() {
    auto* row = new QWidget;
    auto* layout = new QHBoxLayout(row);
    layout->setContentsMargins(0, 0, 0, 0);
    midi_map_ = new QLineEdit(current_.midi_map);
    midi_map_->setObjectName("midi_map");
    midi_map_->setPlaceholderText(
        tr("STK's Bowed: CC 2 force, CC 4 position, CC 1/11 vibrato, pressure speed"));
    auto* choose = new QPushButton(tr("Choose…"));
    connect(choose, &QPushButton::clicked, this, [this] {
        const QString path = QFileDialog::getOpenFileName(
            this, tr("MIDI mapping file"), midi_map_->text(), tr("MIDI maps (*.json)"));
        if (!path.isEmpty()) midi_map_->setText(path);
    });
    layout->addWidget(midi_map_, 1);
    layout->addWidget(choose);
    midi_map_problem_ = new QLabel;
    midi_map_problem_->setObjectName("midi_map_problem");
    midi_map_problem_->setWordWrap(true);
    midi_map_problem_->setStyleSheet("color: #b00020");
    midi_map_problem_->hide();
    return row;
}

void SettingsDialog::accept() {
    const QString map = midi_map_->text().trimmed();
    if (!map.isEmpty()) {
        try {
            midi::load_midi_mapping(map.toStdString());
        } catch (const std::exception& e) {
            midi_map_problem_->setText(QString::fromUtf8(e.what()));
            midi_map_problem_->show();
            return;  // the engine would refuse it: nothing is applied
        }
    }
    QDialog::accept();
}

EngineClientOptions SettingsDialog::options() const {
    EngineClientOptions o = current_;
    o.audio = audio_->currentData().toString();
    o.audio_device = audio_->currentData(kDeviceRole).toInt();
    o.buffer_frames = buffer_->value();
    o.sample_rate = rate_->currentData().toDouble();
    o.haptic = haptic_->currentData().toString();
    o.osc_port = osc_->value();
    o.midi = midi_->currentData().toString();
    o.midi_api = midi_->currentData(kMidiApiRole).toString();
    o.midi_map = midi_map_->text().trimmed();
    return o;
}

}  // namespace archet::ui
