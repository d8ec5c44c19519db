#pragma once
// The mouse as the bow: dragging across the pad moves the sliding axis, dragging down (or the
// wheel) presses the bow into the string. The force the model feeds back is drawn as arrows
// at the bow: the visual stand-in for a force-feedback device. The keyboard's middle row
// plays the left hand: A for the open string, W S E D F T G Y H U J K one semitone up each.

#include <QString>
#include <QWidget>
#include <vector>

namespace archet::ui {

class GesturePad : public QWidget {
    Q_OBJECT

  public:
    explicit GesturePad(QWidget* parent = nullptr);

    /// Where the pad holds the bow (m), as if dragged there.
    void set_position(double slide, double press);
    double slide() const { return slide_; }
    double press() const { return press_; }
    /// The force the model returns on each axis (N), drawn at the bow.
    void set_feedback(double slide_force, double press_force);
    /// Why the pad cannot bow the model (no hand, no bow), written across it; empty when it can.
    void set_notice(const QString& notice);
    const QString& notice() const { return notice_; }

    static constexpr double kSlideRange = 0.15;                     ///< m either side of centre
    static constexpr double kPressMin = -0.003, kPressMax = 0.006;  ///< m; below 0 lifted

    QSize sizeHint() const override { return {420, 260}; }

  signals:
    void moved(double slide, double press);
    /// The player took the bow with the mouse (a stroke playing on its own yields to them).
    void grabbed();
    /// A key of the keyboard row: the finger to `semitones` above the open string (0…12), or
    /// −1 when the last key held is let go (the open string).
    void note(int semitones);

  protected:
    void paintEvent(QPaintEvent*) override;
    void mousePressEvent(QMouseEvent*) override;
    void mouseMoveEvent(QMouseEvent*) override;
    /// Letting go lifts the bow off the string (press back to 0), unless Shift holds it there.
    void mouseReleaseEvent(QMouseEvent*) override;
    void wheelEvent(QWheelEvent*) override;
    /// The row's keys are the pad's while it has the keyboard (F is not Freeze then).
    bool event(QEvent*) override;
    void keyPressEvent(QKeyEvent*) override;
    void keyReleaseEvent(QKeyEvent*) override;
    /// Keys let go elsewhere never come back: the finger returns to the open string.
    void focusOutEvent(QFocusEvent*) override;

  private:
    QRectF area() const;
    double x_of(double slide) const;
    double y_of(double press) const;
    void move_to(QPointF point);

    double slide_ = 0, press_ = 0;
    double slide_force_ = 0, press_force_ = 0;
    QString notice_;
    std::vector<int> held_;  ///< semitones of the keys held, the last one sounding
};

}  // namespace archet::ui
