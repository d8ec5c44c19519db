#pragma once
// The compare view: one gesture rendered offline with two or more values of a parameter
// (string damping by default), side by side as in the paper's Fig. 5 with the energy each
// string dissipates per period, and A/B listening. Rendering runs off the GUI thread and
// can be cancelled.

#include <QDialog>
#include <vector>

#include "archet/analysis/comparison.hpp"
#include "archet/model/model.hpp"
#include "archet/preview_player.hpp"
#include "archet/ui/background_job.hpp"

class QComboBox;
class QHBoxLayout;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;

namespace archet::ui {

class CompareFigure;

class CompareView : public QDialog {
    Q_OBJECT

  public:
    explicit CompareView(const Model& model, QWidget* parent = nullptr);

    void set_variation(const QString& parameter, const QString& values);
    /// Starts rendering (as the Render button does).
    void render();
    bool busy() const { return job_.busy(); }
    const std::vector<ComparisonRun>& runs() const { return runs_; }
    CompareFigure& figure() { return *figure_; }
    PreviewPlayer& player() { return player_; }

  signals:
    void rendered();

  private:
    void finish(std::vector<ComparisonRun> runs, QString error);
    void show_listen_buttons();
    void export_figure();

    Model model_;
    Gesture gesture_;
    QComboBox* parameter_;
    QLineEdit* values_;
    QPushButton* render_;
    QPushButton* cancel_;
    QProgressBar* progress_;
    QLabel* message_;
    CompareFigure* figure_;
    QHBoxLayout* listen_;
    std::vector<ComparisonRun> runs_;
    PreviewPlayer player_;  ///< the preview path, apart from the engine
    BackgroundJob job_;     ///< last: destroyed (cancelled and joined) first
};

}  // namespace archet::ui
