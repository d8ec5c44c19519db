#include "archet/midi/midi_performer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "archet/common/number_text.hpp"

namespace archet::midi {

namespace {

// A note may lie this far below the open string and still be played open: the string's own
// tuning is rarely equal-tempered to the cent.
const double kOpenTolerance = std::pow(2.0, 0.5 / 12);  // half a semitone
constexpr double kHighestShare = 1.0 / 16;              // four octaves above the open string

double note_hz(int note) {
    return 440.0 * std::pow(2.0, (note - 69) / 12.0);
}

double scaled(const ControlRoute& r, int value) {
    return r.minimum + (r.maximum - r.minimum) * value / 127.0;
}

}  // namespace

MidiPerformer::MidiPerformer(MidiMapping mapping, PerformedModel model)
    : mapping_(std::move(mapping)), model_(std::move(model)), speed_(mapping_.bow_speed) {}

bool MidiPerformer::heard(const MidiMessage& m) const {
    return mapping_.channel == 0 || m.channel == mapping_.channel;
}

std::optional<double> MidiPerformer::finger_position(int note) const {
    const double share = model_.open_string_hz / note_hz(note);
    if (share > kOpenTolerance || share < kHighestShare) return std::nullopt;
    return std::min(share, 1.0);
}

void MidiPerformer::receive(const MidiMessage& m) {
    if (!heard(m)) return;
    using K = MidiMessage::Kind;
    switch (m.kind) {
        case K::NoteOn:
            return note_on(m.number, m.value);
        case K::NoteOff:
            return note_off(m.number);
        case K::Control:
            return control(m.number, m.value);
        case K::ChannelPressure:
            return control(kChannelPressure, m.value);
        case K::PitchBend:
            bend_ = m.value / 8192.0 * mapping_.bend_range;
            return;
    }
}

void MidiPerformer::note_on(int note, int velocity) {
    if (!model_.finger.empty() && !finger_position(note))
        return refuse({Refusal::Why::OutOfReach, note});
    if (held_count_ == 0) {  // a new stroke, the other way, at the note's force
        direction_ = -direction_;
        velocity_force_ =
            mapping_.velocity_force_min +
            (mapping_.velocity_force_max - mapping_.velocity_force_min) * (velocity - 1) / 126.0;
    }
    release(note);
    held_[held_count_++] = note;  // at most 128 distinct notes, each held once
    sounding_ = note;
}

void MidiPerformer::note_off(int note) {
    release(note);
    if (held_count_ > 0) sounding_ = held_[held_count_ - 1];
}

void MidiPerformer::release(int note) {
    const auto end = held_.begin() + static_cast<std::ptrdiff_t>(held_count_);
    held_count_ = static_cast<std::size_t>(std::remove(held_.begin(), end, note) - held_.begin());
}

void MidiPerformer::set(MidiTarget target, double value) {
    switch (target) {
        case MidiTarget::BowForce:
            controlled_force_ = value;
            return;
        case MidiTarget::BowSpeed:
            speed_ = value;
            return;
        case MidiTarget::VibratoDepth:
            vibrato_depth_ = value;
            return;
        case MidiTarget::VibratoRate:
            vibrato_rate_ = value;
            return;
        case MidiTarget::FingerPressure:
        case MidiTarget::BowPosition:
        case MidiTarget::Parameter:
            return;  // asked of the model, by control()
    }
}

void MidiPerformer::control(int controller, int value) {
    const ControlRoute* route = mapping_.route(controller);
    if (!route) return;  // unmapped controllers (a sustain pedal, say) play no part
    const double v = scaled(*route, value);
    if (route->target == MidiTarget::FingerPressure) {
        if (model_.finger.empty()) return refuse({Refusal::Why::NoFinger, controller});
        return request({ParameterRequest::What::FingerPressure, -1, v});
    }
    if (route->target == MidiTarget::BowPosition)
        return request({ParameterRequest::What::BowPosition, -1, v});
    if (route->target == MidiTarget::Parameter)
        return request(
            {ParameterRequest::What::Route, static_cast<int>(route - mapping_.controls.data()), v});
    set(route->target, v);
}

// Of the requests of one round, the newest value of each parameter acts.
void MidiPerformer::request(ParameterRequest r) {
    for (std::size_t i = 0; i < pending_.request_count; ++i) {
        ParameterRequest& known = pending_.requests[i];
        if (known.what == r.what && known.route == r.route) {
            known.value = r.value;
            return;
        }
    }
    if (pending_.request_count < pending_.requests.size())
        pending_.requests[pending_.request_count++] = r;
}

void MidiPerformer::refuse(Refusal r) {
    if (pending_.refusal_count < pending_.refusals.size())
        pending_.refusals[pending_.refusal_count++] = r;
    else
        ++pending_.refusals_lost;
}

void MidiPerformer::take_over(const MidiPerformer& o) {
    slide_speed_ = o.slide_speed_, press_ = o.press_;
    held_ = o.held_, held_count_ = o.held_count_;
    direction_ = o.direction_;
    velocity_force_ = o.velocity_force_, controlled_force_ = o.controlled_force_;
    speed_ = o.speed_;
    vibrato_depth_ = o.vibrato_depth_, vibrato_rate_ = o.vibrato_rate_;
    vibrato_phase_ = o.vibrato_phase_;
    bend_ = o.bend_, finger_set_ = o.finger_set_, sounding_ = o.sounding_;
    pending_ = o.pending_;
    mapping_.velocity_force_min = o.mapping_.velocity_force_min;
    mapping_.velocity_force_max = o.mapping_.velocity_force_max;
}

double MidiPerformer::force() const {
    return controlled_force_ >= 0 ? controlled_force_ : velocity_force_;
}

MidiPerformer::Round MidiPerformer::advance(double seconds) {
    const double speed = held_count_ == 0 ? 0.0 : direction_ * speed_;
    const double press = held_count_ == 0 ? 0.0 : force() / model_.newtons_per_press;
    pending_.bow_changed = speed != slide_speed_ || press != press_;
    pending_.slide_speed = slide_speed_ = speed;
    pending_.press = press_ = press;
    vibrato_phase_ = std::fmod(vibrato_phase_ + 2 * std::numbers::pi * vibrato_rate_ * seconds,
                               2 * std::numbers::pi);
    if (!model_.finger.empty() && sounding_ >= 0) {
        const double semitones = bend_ + vibrato_depth_ * std::sin(vibrato_phase_);
        const double position =
            std::clamp(*finger_position(sounding_) * std::pow(2.0, -semitones / 12), 0.0, 1.0);
        if (position != finger_set_) {
            request({ParameterRequest::What::FingerPosition, -1, position});
            finger_set_ = position;
        }
    }
    Round round = pending_;
    pending_ = Round{};
    return round;
}

ParameterName MidiPerformer::parameter_of(const ParameterRequest& r) const {
    switch (r.what) {
        case ParameterRequest::What::FingerPosition:
            return {model_.finger, "position"};
        case ParameterRequest::What::FingerPressure:
            return {model_.finger, "pressure"};
        case ParameterRequest::What::BowPosition:
            return {"bow", "position"};  // a variant of the model (model_variants.hpp)
        case ParameterRequest::What::Route:
            break;
    }
    return mapping_.controls.at(static_cast<std::size_t>(r.route)).parameter;
}

std::string MidiPerformer::describe(const Refusal& r) const {
    if (r.why == Refusal::Why::NoFinger)
        return "controller " + std::to_string(r.number) +
               " moves the finger's pressure, and this model has no finger "
               "(archet new bowed-string --finger)";
    return "note " + std::to_string(r.number) + " (" +
           format_number(std::round(note_hz(r.number))) +
           " Hz) is out of this string's reach: its open string is " +
           format_number(std::round(model_.open_string_hz * 10) / 10) +
           " Hz and the finger stops it up to four octaves higher";
}

}  // namespace archet::midi
