#pragma once
// The pieces the panels that sweep a grid in the background share (the playability and attack
// maps): number fields, a MIN … MAX in STEPS row, and Compute / Cancel with a progress bar
// that follows the job.

#include <QString>

class QDoubleSpinBox;
class QHBoxLayout;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QWidget;

namespace archet::ui {

class BackgroundJob;

QDoubleSpinBox* number_box(double lo, double hi, double value, int decimals, const QString& suffix);
QSpinBox* count_box(int lo, int hi, int value);
/// "lo … hi in steps" on one row.
QHBoxLayout* range_row(QWidget* lo, QWidget* hi, QWidget* steps);

/// Compute, Cancel (off until a job runs) and a progress bar that follows `job`'s reports.
struct SweepButtons {
    QPushButton *compute, *cancel;
    QProgressBar* progress;
    QHBoxLayout* row;
};
SweepButtons sweep_buttons(BackgroundJob& job, QWidget* owner);

/// What a panel says when the open model changes under the map it shows.
QString model_changed_text();

/// Which edit of the open model a panel's map was computed for: a map of an older one says so
/// under every message the panel writes.
struct MapFreshness {
    int model = 0;  ///< bumped at each change of the open model
    int shown = 0;  ///< `model` when the map shown was computed
    bool stale() const { return model != shown; }
    QString note(const QString& message) const {
        return stale() ? message + " " + model_changed_text() : message;
    }
};

}  // namespace archet::ui
