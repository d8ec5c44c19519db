#pragma once
// While a take records: a red "● REC m:ss" in the status bar, counting; hidden otherwise.

#include <QElapsedTimer>
#include <QLabel>
#include <QTimer>

namespace archet::ui {

class RecordingClock : public QLabel {
    Q_OBJECT

  public:
    explicit RecordingClock(QWidget* parent = nullptr);
    void start();
    void stop();

  private:
    void tick();

    QTimer timer_;
    QElapsedTimer since_;
};

}  // namespace archet::ui
