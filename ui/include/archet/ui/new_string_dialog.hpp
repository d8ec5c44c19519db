#pragma once
// "New bowed string": a bowed string from a few choices (pitch, the string's material, tuning,
// structure, masses or the paper's chaplet, body, bow position, decays), built and tuned by the
// same builder as `archet new bowed-string`.

#include <QDialog>

#include "archet/builders/bowed_string.hpp"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QSpinBox;

namespace archet::ui {

class NewStringDialog : public QDialog {
    Q_OBJECT

  public:
    explicit NewStringDialog(QWidget* parent = nullptr);
    BowedStringOptions options() const;

  private:
    void make_material_fields();
    void make_loss_fields();
    void lay_out();
    QDoubleSpinBox* pitch_;
    QDoubleSpinBox* tension_;
    QDoubleSpinBox* density_;
    QLabel* length_;
    QComboBox* tuning_;
    QComboBox* structure_;
    QCheckBox* paper_;
    QCheckBox* finger_;
    QSpinBox* masses_;
    QComboBox* body_;
    QDoubleSpinBox* bow_position_;
    QDoubleSpinBox* t60_;
    QDoubleSpinBox* t60_high_;
    QDoubleSpinBox* t60_high_hz_;
    QDoubleSpinBox* damping_;
};

}  // namespace archet::ui
