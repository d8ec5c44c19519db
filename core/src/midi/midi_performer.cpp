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
    if (!model_.finger.empty() && !finger_position(note)) {
        pending_.refusals.push_back("note " + std::to_string(note) + " (" +
                                    format_number(std::round(note_hz(note))) +
                                    " Hz) is out of this string's reach: its open string is " +
                                    format_number(std::round(model_.open_string_hz * 10) / 10) +
                                    " Hz and the finger stops it up to four octaves higher");
        return;
    }
    if (held_.empty()) {  // a new stroke, the other way, at the note's force
        direction_ = -direction_;
        velocity_force_ =
            mapping_.velocity_force_min +
            (mapping_.velocity_force_max - mapping_.velocity_force_min) * (velocity - 1) / 126.0;
    }
    std::erase(held_, note);
    held_.push_back(note);
    sounding_ = note;
}

void MidiPerformer::note_off(int note) {
    std::erase(held_, note);
    if (!held_.empty()) sounding_ = held_.back();
}

void MidiPerformer::control(int controller, int value) {
    const ControlRoute* route = mapping_.route(controller);
    if (!route) return;  // unmapped controllers (a sustain pedal, say) play no part
    const double v = scaled(*route, value);
    switch (route->target) {
        case MidiTarget::BowForce:
            controlled_force_ = v;
            return;
        case MidiTarget::BowSpeed:
            speed_ = v;
            return;
        case MidiTarget::VibratoDepth:
            vibrato_depth_ = v;
            return;
        case MidiTarget::VibratoRate:
            vibrato_rate_ = v;
            return;
        case MidiTarget::FingerPressure:
            if (model_.finger.empty()) {
                pending_.refusals.push_back("controller " + std::to_string(controller) +
                                            " moves the finger's pressure, and this model has "
                                            "no finger (archet new bowed-string --finger)");
                return;
            }
            pending_.parameters.push_back({{model_.finger, "pressure"}, v});
            return;
        case MidiTarget::Parameter:
            pending_.parameters.push_back({route->parameter, v});
            return;
    }
}

double MidiPerformer::force() const {
    return controlled_force_ >= 0 ? controlled_force_ : velocity_force_;
}

MidiPerformer::Round MidiPerformer::advance(double seconds) {
    Round round = std::move(pending_);
    pending_ = {};
    const double speed = held_.empty() ? 0.0 : direction_ * speed_;
    const double press = held_.empty() ? 0.0 : force() / model_.newtons_per_press;
    round.bow_changed = speed != slide_speed_ || press != press_;
    round.slide_speed = slide_speed_ = speed;
    round.press = press_ = press;
    vibrato_phase_ = std::fmod(vibrato_phase_ + 2 * std::numbers::pi * vibrato_rate_ * seconds,
                               2 * std::numbers::pi);
    if (!model_.finger.empty() && sounding_ >= 0) {
        const double semitones = bend_ + vibrato_depth_ * std::sin(vibrato_phase_);
        const double position =
            std::clamp(*finger_position(sounding_) * std::pow(2.0, -semitones / 12), 0.0, 1.0);
        if (position != finger_set_) {
            round.parameters.insert(round.parameters.begin(),
                                    {{model_.finger, "position"}, position});
            finger_set_ = position;
        }
    }
    return round;
}

}  // namespace archet::midi
