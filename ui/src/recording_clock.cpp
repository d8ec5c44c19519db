#include "archet/ui/recording_clock.hpp"

namespace archet::ui {

RecordingClock::RecordingClock(QWidget* parent) : QLabel(parent) {
    setObjectName("recording");
    setStyleSheet(
        "QLabel { color: white; background: #c0392b; border-radius: 4px; padding: 1px 8px; "
        "font-weight: bold; }");
    setToolTip(tr("A take is being recorded (R stops it)"));
    hide();
    connect(&timer_, &QTimer::timeout, this, &RecordingClock::tick);
}

void RecordingClock::start() {
    since_.start();
    timer_.start(200);
    tick();
    show();
}

void RecordingClock::stop() {
    timer_.stop();
    hide();
}

void RecordingClock::tick() {
    const qint64 seconds = since_.elapsed() / 1000;
    setText(tr("● REC %1:%2").arg(seconds / 60).arg(seconds % 60, 2, 10, QLatin1Char('0')));
}

}  // namespace archet::ui
