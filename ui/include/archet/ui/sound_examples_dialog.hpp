#pragma once
// "Render sound examples": the paper's set (see sound_examples.hpp) rendered offline into a
// folder, off the GUI thread, with a progress bar and cancel.

#include <QDialog>

#include "archet/ui/background_job.hpp"

class QLabel;
class QLineEdit;
class QListWidget;
class QProgressBar;
class QPushButton;

namespace archet::ui {

class SoundExamplesDialog : public QDialog {
    Q_OBJECT

  public:
    /// `resources` holds models/ and gestures/.
    SoundExamplesDialog(QString resources, QString folder, QWidget* parent = nullptr);

    void start();
    void cancel() { job_.cancel(); }
    bool busy() const { return job_.busy(); }
    int rendered() const { return rendered_; }

  signals:
    void finished_rendering(int rendered, const QString& error);

  private:
    void done(int rendered, const QString& error);

    QString resources_;
    QLineEdit* folder_;
    QListWidget* list_;
    QProgressBar* progress_;
    QLabel* message_;
    QPushButton* start_;
    QPushButton* cancel_;
    int rendered_ = 0;   ///< so far, as the job reports them
    BackgroundJob job_;  ///< last: destroyed (cancelled and joined) first
};

}  // namespace archet::ui
