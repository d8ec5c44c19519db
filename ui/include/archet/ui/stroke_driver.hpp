#pragma once
// A stroke from rest at a chosen acceleration, played on the gesture pad: the way to try an
// attack of the attack map by hand. The pad's bow slides from where it is towards the far side
// with constant acceleration, at the pad's press, until it reaches the edge, is stopped, or the
// player takes the bow with the mouse.

#include <QElapsedTimer>
#include <QObject>

class QTimer;

namespace archet::ui {

class GesturePad;

class StrokeDriver : public QObject {
    Q_OBJECT

  public:
    explicit StrokeDriver(GesturePad& pad, QObject* parent = nullptr);

    /// Starts a stroke at `acceleration` (m/s², > 0) from the pad's current position.
    void start(double acceleration);
    void stop();
    bool running() const;

  signals:
    void finished();

  private:
    void advance();

    GesturePad& pad_;
    QTimer* timer_;
    QElapsedTimer clock_;
    double acceleration_ = 0, from_ = 0, direction_ = 1;
};

}  // namespace archet::ui
