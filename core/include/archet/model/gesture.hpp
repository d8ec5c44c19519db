#pragma once
// A player's gesture: keyframes of the device's two axes over time, linearly interpolated.
// `slide` is the bow's transverse position and `press` the pressure axis (both in metres,
// device coordinates; gesture points scale them into the model).

#include <string>
#include <vector>

namespace archet {

struct GestureKeyframe {
    double time = 0.0;   ///< s
    double slide = 0.0;  ///< m
    double press = 0.0;  ///< m
};

inline bool operator==(const GestureKeyframe& a, const GestureKeyframe& b) {
    return a.time == b.time && a.slide == b.slide && a.press == b.press;
}

struct GestureSample {
    double slide = 0.0;
    double press = 0.0;
};

class Gesture {
  public:
    Gesture() = default;
    /// Keyframes must be in strictly increasing time (validated by the loader).
    Gesture(std::string name, std::vector<GestureKeyframe> keyframes);

    /// Axis positions at time t; held at the first/last keyframe outside their range. It moves
    /// a cursor kept in the gesture: two threads reading one gesture at once need a copy each.
    GestureSample at(double t) const;
    double duration() const { return keyframes_.empty() ? 0.0 : keyframes_.back().time; }
    bool empty() const { return keyframes_.empty(); }

    const std::string& name() const { return name_; }
    const std::vector<GestureKeyframe>& keyframes() const { return keyframes_; }
    bool operator==(const Gesture& other) const {
        return name_ == other.name_ && keyframes_ == other.keyframes_;
    }

  private:
    std::string name_;
    std::vector<GestureKeyframe> keyframes_;
    // Sequential reads (rendering) walk forward from the last segment found.
    mutable std::size_t cursor_ = 0;
};

/// A clean steady stroke: press lands, the bow accelerates to `speed`, holds, and lifts.
Gesture steady_bow_gesture(double speed = 0.1, double press = 0.0015, double duration = 3.0);

}  // namespace archet
