#include "archet/ui/gesture_pad.hpp"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

namespace archet::ui {

namespace {
constexpr double kNewtonsToPixels = 80;  // arrow length per newton of fed-back force
constexpr double kWheelStep = 0.0001;    // m of pressure per wheel notch

void arrow(QPainter& p, QPointF from, QPointF to) {
    const QLineF line(from, to);
    if (line.length() < 2) return;
    p.drawLine(line);
    const double angle = std::atan2(-line.dy(), line.dx());
    const double head = 8;
    QPainterPath tip;
    tip.moveTo(to);
    tip.lineTo(to - QPointF(std::cos(angle + 0.45) * head, -std::sin(angle + 0.45) * head));
    tip.lineTo(to - QPointF(std::cos(angle - 0.45) * head, -std::sin(angle - 0.45) * head));
    tip.closeSubpath();
    p.fillPath(tip, p.pen().color());
}
}  // namespace

GesturePad::GesturePad(QWidget* parent) : QWidget(parent) {
    setMinimumSize(240, 160);
    setFocusPolicy(Qt::WheelFocus);
    setToolTip(
        tr("Drag across to bow, down to press the bow into the string (or use the "
           "wheel); let go to lift the bow, or hold Shift as you let go to keep it "
           "pressed. With a finger on the string, the keys A W S E D F T G Y H U J K stop it "
           "a semitone higher each, from the open string to the octave"));
}

QRectF GesturePad::area() const {
    return QRectF(rect()).adjusted(12, 36, -12, -12);
}

double GesturePad::x_of(double slide) const {
    const QRectF a = area();
    return a.left() + (slide + kSlideRange) / (2 * kSlideRange) * a.width();
}

double GesturePad::y_of(double press) const {
    const QRectF a = area();
    return a.top() + (press - kPressMin) / (kPressMax - kPressMin) * a.height();
}

void GesturePad::set_position(double slide, double press) {
    slide_ = std::clamp(slide, -kSlideRange, kSlideRange);
    press_ = std::clamp(press, kPressMin, kPressMax);
    update();
    emit moved(slide_, press_);
}

void GesturePad::set_feedback(double slide_force, double press_force) {
    slide_force_ = slide_force, press_force_ = press_force;
    update();
}

void GesturePad::move_to(QPointF point) {
    const QRectF a = area();
    const double u = (point.x() - a.left()) / a.width(), v = (point.y() - a.top()) / a.height();
    set_position(-kSlideRange + u * 2 * kSlideRange, kPressMin + v * (kPressMax - kPressMin));
}

void GesturePad::mousePressEvent(QMouseEvent* e) {
    emit grabbed();
    move_to(e->position());
}

void GesturePad::mouseMoveEvent(QMouseEvent* e) {
    if (e->buttons() & Qt::LeftButton) move_to(e->position());
}

void GesturePad::mouseReleaseEvent(QMouseEvent* e) {
    if (e->button() == Qt::LeftButton && !(e->modifiers() & Qt::ShiftModifier) && press_ > 0)
        set_position(slide_, 0);
}

void GesturePad::set_notice(const QString& notice) {
    notice_ = notice;
    update();
}

void GesturePad::wheelEvent(QWheelEvent* e) {
    const double notches = e->angleDelta().y() / 120.0;
    set_position(slide_, press_ - notches * kWheelStep);  // wheel up lifts the bow
    e->accept();
}

namespace {

// The keyboard row, a semitone per key as on a piano's white and black keys: A W S E D F T G
// Y H U J K, the open string to the octave.
int semitones_of(int key) {
    static const QString row = "AWSEDFTGYHUJK";
    return key >= Qt::Key_A && key <= Qt::Key_Z ? static_cast<int>(row.indexOf(QChar(key))) : -1;
}

}  // namespace

bool GesturePad::event(QEvent* e) {
    if (e->type() == QEvent::ShortcutOverride) {
        const auto* key = static_cast<QKeyEvent*>(e);
        if (semitones_of(key->key()) >= 0 && !(key->modifiers() & ~Qt::KeypadModifier)) {
            e->accept();
            return true;
        }
    }
    return QWidget::event(e);
}

void GesturePad::focusOutEvent(QFocusEvent* e) {
    if (!held_.empty()) {
        held_.clear();
        update();
        emit note(-1);
    }
    QWidget::focusOutEvent(e);
}

void GesturePad::keyPressEvent(QKeyEvent* e) {
    const int n = semitones_of(e->key());
    if (n < 0 || e->modifiers() & ~Qt::KeypadModifier) return QWidget::keyPressEvent(e);
    if (e->isAutoRepeat()) return;
    std::erase(held_, n);
    held_.push_back(n);
    update();
    emit note(n);
}

void GesturePad::keyReleaseEvent(QKeyEvent* e) {
    const int n = semitones_of(e->key());
    if (n < 0 || e->isAutoRepeat()) return QWidget::keyReleaseEvent(e);
    const bool sounding = !held_.empty() && held_.back() == n;
    std::erase(held_, n);
    update();
    if (sounding) emit note(held_.empty() ? -1 : held_.back());  // back to the key still held
}

void GesturePad::paintEvent(QPaintEvent*) {
    QPainter p(this);
    p.setRenderHint(QPainter::Antialiasing);
    const QRectF a = area();
    p.fillRect(rect(), palette().base());
    p.setPen(QPen(palette().mid().color(), 1));
    p.drawRect(a);
    // The string, seen from the side: the bow touches it at press 0.
    const double string_y = y_of(0);
    p.setPen(QPen(QColor(150, 110, 40), 3));
    p.drawLine(QPointF(a.left(), string_y), QPointF(a.right(), string_y));
    // The bow: a vertical hair at its slide position, its tip at its press.
    const QPointF tip(x_of(slide_), y_of(press_));
    p.setPen(QPen(palette().text().color(), 2));
    p.drawLine(QPointF(tip.x(), a.top()), tip);
    p.setBrush(press_ > 0 ? QColor(200, 60, 40) : palette().text().color());
    p.drawEllipse(tip, 5, 5);
    // The force the string pushes back with, on each axis.
    p.setPen(QPen(QColor(30, 110, 200), 2));
    p.setClipRect(a);
    arrow(p, tip, tip + QPointF(slide_force_ * kNewtonsToPixels, 0));
    arrow(p, tip, tip + QPointF(0, press_force_ * kNewtonsToPixels));
    p.setClipping(false);
    p.setPen(palette().text().color());
    p.drawText(QRectF(rect()).adjusted(12, 2, -12, 0), Qt::AlignLeft | Qt::AlignTop,
               tr("bow at %1 mm, pressed %2 mm\nthe string pushes back %3 N, %4 N")
                   .arg(slide_ * 1000, 0, 'f', 1)
                   .arg(press_ * 1000, 0, 'f', 2)
                   .arg(slide_force_, 0, 'f', 2)
                   .arg(press_force_, 0, 'f', 2));
    if (!held_.empty())
        p.drawText(QRectF(rect()).adjusted(12, 2, -12, 0), Qt::AlignRight | Qt::AlignTop,
                   tr("finger: %1 semitones up").arg(held_.back()));
    if (!notice_.isEmpty()) {
        QColor veil = palette().window().color();
        veil.setAlpha(220);
        p.fillRect(a, veil);
        p.setPen(palette().windowText().color());
        p.drawText(a.adjusted(16, 16, -16, -16), Qt::AlignCenter | Qt::TextWordWrap, notice_);
    }
}

}  // namespace archet::ui
