#pragma once
// "Render sound examples": the paper's set (see sound_examples.hpp) rendered offline into a
// folder, off the GUI thread, with a progress bar and cancel.

#include <QDialog>
#include <atomic>
#include <thread>

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
    ~SoundExamplesDialog() override;

    void start();
    void cancel() { cancel_requested_.store(true); }
    bool busy() const { return running_.load(); }
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
    std::thread worker_;
    std::atomic<bool> cancel_requested_{false}, running_{false};
    int rendered_ = 0;
};

}  // namespace archet::ui
