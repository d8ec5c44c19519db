#include "archet/ui/stroke_driver.hpp"

#include <QTimer>
#include <algorithm>

#include "archet/ui/gesture_pad.hpp"

namespace archet::ui {

StrokeDriver::StrokeDriver(GesturePad& pad, QObject* parent) : QObject(parent), pad_(pad) {
    timer_ = new QTimer(this);
    timer_->setTimerType(Qt::PreciseTimer);
    timer_->setInterval(2);  // ms; the position follows the clock, not the ticks
    connect(timer_, &QTimer::timeout, this, &StrokeDriver::advance);
    connect(&pad_, &GesturePad::grabbed, this, &StrokeDriver::stop);  // the player takes over
}

void StrokeDriver::start(double acceleration) {
    if (!(acceleration > 0)) return;
    acceleration_ = acceleration;
    from_ = pad_.slide();
    direction_ = from_ <= 0 ? 1.0 : -1.0;  // towards the far side: the longest stroke
    clock_.start();
    timer_->start();
}

void StrokeDriver::stop() {
    if (!timer_->isActive()) return;
    timer_->stop();
    emit finished();
}

bool StrokeDriver::running() const {
    return timer_->isActive();
}

void StrokeDriver::advance() {
    const double t = static_cast<double>(clock_.nsecsElapsed()) * 1e-9;
    const double edge = direction_ * GesturePad::kSlideRange;
    double slide = from_ + direction_ * 0.5 * acceleration_ * t * t;
    const bool at_edge = direction_ > 0 ? slide >= edge : slide <= edge;
    if (at_edge) slide = edge;
    pad_.set_position(slide, pad_.press());
    if (at_edge) stop();
}

}  // namespace archet::ui
