#pragma once
// "New bowed string": the paper's string from a few choices (pitch, tuning, structure, masses,
// bow position, decay), built and tuned by the same builder as `archet new bowed-string`.

#include <QDialog>

#include "archet/builders/bowed_string.hpp"

class QComboBox;
class QDoubleSpinBox;
class QSpinBox;

namespace archet::ui {

class NewStringDialog : public QDialog {
    Q_OBJECT

  public:
    explicit NewStringDialog(QWidget* parent = nullptr);
    BowedStringOptions options() const;

  private:
    QDoubleSpinBox* pitch_;
    QComboBox* tuning_;
    QComboBox* structure_;
    QSpinBox* masses_;
    QDoubleSpinBox* bow_position_;
    QDoubleSpinBox* t60_;
    QDoubleSpinBox* damping_;
};

}  // namespace archet::ui
