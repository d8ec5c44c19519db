#include "archet/model/gesture.hpp"

namespace archet {

Gesture::Gesture(std::string name, std::vector<GestureKeyframe> keyframes)
    : name_(std::move(name)), keyframes_(std::move(keyframes)) {}

GestureSample Gesture::at(double t) const {
    if (keyframes_.empty()) return {};
    if (t <= keyframes_.front().time) return {keyframes_.front().slide, keyframes_.front().press};
    if (t >= keyframes_.back().time) return {keyframes_.back().slide, keyframes_.back().press};
    if (cursor_ + 1 >= keyframes_.size() || keyframes_[cursor_].time > t) cursor_ = 0;
    while (keyframes_[cursor_ + 1].time < t) ++cursor_;
    const auto& a = keyframes_[cursor_];
    const auto& b = keyframes_[cursor_ + 1];
    // On a keyframe, exactly its values (a recorded take replays bit for bit).
    if (t == b.time) return {b.slide, b.press};
    const double u = (t - a.time) / (b.time - a.time);
    return {a.slide + u * (b.slide - a.slide), a.press + u * (b.press - a.press)};
}

}  // namespace archet
