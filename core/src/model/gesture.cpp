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

Gesture steady_bow_gesture(double speed, double press, double duration) {
    const double land = 0.03, accelerate = 0.1, lift = duration - 0.4;
    std::vector<GestureKeyframe> k;
    k.push_back({0.0, 0.0, 0.0});     // bow resting on the string
    k.push_back({land, 0.0, press});  // lands
    k.push_back({land + accelerate / 2, speed * accelerate / 8, press});  // speeds up
    k.push_back({land + accelerate, speed * accelerate / 2, press});
    const double x_lift = speed * accelerate / 2 + speed * (lift - land - accelerate);
    k.push_back({lift, x_lift, press});                          // steady stroke
    k.push_back({lift + 0.05, x_lift + speed * 0.025, -0.002});  // lifts off
    k.push_back({duration, x_lift + speed * 0.025, -0.002});
    return Gesture("steady bow", std::move(k));
}

}  // namespace archet
