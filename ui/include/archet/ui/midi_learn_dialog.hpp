#pragma once
// MIDI learn: the mapping the engine plays MIDI with, as a table of controllers and what each
// moves, edited by doing: choose what to move (the bow's force or speed, vibrato, the finger's
// pressure, or any parameter of the model), move a controller on the keyboard, set the range,
// assign. Saved as a mapping file (docs/midi.md) that the engine then plays with.

#include <QDialog>

#include "archet/midi/midi_mapping.hpp"
#include "archet/model/model.hpp"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QTableWidget;

namespace archet::ui {

class MidiLearnDialog : public QDialog {
    Q_OBJECT

  public:
    MidiLearnDialog(midi::MidiMapping mapping, const Model& model, QWidget* parent = nullptr);

    /// A controller moved (from EngineClient::midi_controller): the one to assign.
    void heard(int controller, const QString& said);
    /// Assigns the controller last heard to the chosen target and range.
    void assign();
    /// Writes the mapping to `path` (checked as the engine will read it); false with the
    /// reason shown when it cannot.
    bool save_to(const QString& path);

    const midi::MidiMapping& mapping() const { return mapping_; }
    QString saved_path() const { return saved_; }

  private:
    void choose_target();
    void fill_table();
    void remove_selected();
    void save();

    midi::MidiMapping mapping_;
    Model model_;
    int heard_ = -1;  ///< the controller last moved (−1: none yet)
    QString saved_;
    QTableWidget* table_;
    QComboBox* target_;
    QDoubleSpinBox *minimum_, *maximum_;
    QLabel *heard_label_, *problem_;
    QPushButton* assign_;
};

}  // namespace archet::ui
