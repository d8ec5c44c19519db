#include "lv2_instrument.hpp"

#include <algorithm>
#include <cmath>

#include "archet/model/model_parameters.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/model_variants.hpp"
#include "archet/physics/chain_build_choice.hpp"

namespace archet::lv2 {

namespace {

// The model with its bow at β (0: where it is), checked.
Model prepared(Model model, double beta) {
    if (beta > 0) set_variant_parameter(model, "bow.position", beta);
    validate_model(model);
    return model;
}

// Every damper along the string: its links' and its masses' losses to rest.
std::vector<ParameterName> string_dampers(const Model& model) {
    std::vector<ParameterName> names;
    for (const auto& id : string_links(model)) names.push_back({id, "damping"});
    for (const auto& id : string_masses(model))
        if (const Mat* m = model.find_mat(id); m && m->kind == MatKind::Oscillator)
            names.push_back({id, "damping"});
    return names;
}

// The largest factor of the string's damping (of 10, 5, 3, 2, 1.5) at which the model still
// validates: the scheme's stability bound and the parameters' ranges. The port is held to it.
double largest_damping_scale(const Model& model, const std::vector<ParameterName>& dampers) {
    for (double scale : {10.0, 5.0, 3.0, 2.0, 1.5}) {
        try {
            Model scaled = model;
            for (const ParameterName& n : dampers)
                set_parameter(scaled, n, get_parameter(model, n) * scale);
            validate_model(scaled);
            return scale;
        } catch (const std::exception&) {
        }
    }
    return 1.0;
}

}  // namespace

Instrument::Instrument(Model model, double sample_rate, double bow_position,
                       std::optional<ChainBuild> build)
    : model_(prepared(std::move(model), bow_position)),
      sim_(compile(model_, sample_rate)),
      performer_(midi::default_midi_mapping(), midi::performed_model(model_)),
      limiter_(sample_rate),
      bow_position_(bow_position) {
    if (const Lia* finger = first_finger(model_))
        for (const char* p : {"position", "pressure"})
            finger_slots_.push_back(sim_.model().resolve_parameter({finger->id, p}));
    const std::vector<ParameterName> dampers = string_dampers(model_);
    for (const ParameterName& name : dampers)
        damping_.push_back({sim_.model().resolve_parameter(name), get_parameter(model_, name)});
    largest_damping_scale_ = largest_damping_scale(model_, dampers);
    if (const CompiledLevel* hand = hand_level(sim_.model()))
        haptic_divider_ = static_cast<std::uint64_t>(hand->divider), haptic_dt_ = hand->dt;
    glide_samples_ = static_cast<int>(std::lround(0.01 * sample_rate));  // 10 ms, as the engine
    state_.resize(sim_.state_size());
    sim_.set_chain_build(build ? *build : fastest_chain_build(sim_));  // never on the audio thread
}

void Instrument::set_controls(double bow_force, double bow_speed, double damping_scale) {
    if (bow_force != bow_force_) performer_.set_velocity_force(0.25 * bow_force, bow_force);
    if (bow_speed != bow_speed_) performer_.set(midi::MidiTarget::BowSpeed, bow_speed);
    bow_force_ = bow_force, bow_speed_ = bow_speed;
    damping_scale = std::min(damping_scale, largest_damping_scale_);  // stable at the rate
    if (damping_scale == damping_scale_) return;
    damping_scale_ = damping_scale;
    for (const Damping& d : damping_) sim_.write_slot(d.slot, d.base * damping_scale);
    sim_.refresh_uniform_runs();  // the string's MATs are alike again
}

void Instrument::apply_round(double seconds) {
    const midi::MidiPerformer::Round round = performer_.advance(seconds);
    if (round.bow_changed) hand_.press = round.press, drive_speed_ = round.slide_speed;
    using What = midi::ParameterRequest::What;
    for (const midi::ParameterRequest& r : round.parameters()) {
        // The default map routes no parameter of its own: the finger, and the bow's position,
        // which the plugin has the worker build.
        if (r.what == What::BowPosition) bow_request_ = r.value;
        if ((r.what != What::FingerPosition && r.what != What::FingerPressure) ||
            finger_slots_.empty())
            continue;
        const bool position = r.what == What::FingerPosition;
        smoother_.glide(sim_, finger_slots_[position ? 0 : 1], r.value, glide_samples_);
    }
}

void Instrument::drive_hand() {
    hand_.slide += drive_speed_ * haptic_dt_;
    sim_.set_device_position(hand_);
}

// In runs up to the hand's next tick, where it is driven on (a tick at a time while a glide
// moves a parameter): Simulation::run() then takes a bowed string's own loop.
void Instrument::render(float* out, std::uint32_t frames) {
    apply_round(frames / sim_.sample_rate());
    for (std::uint32_t i = 0; i < frames;) {
        if (blown_up_) {
            std::fill(out + i, out + frames, 0.0f);
            return;
        }
        smoother_.advance(sim_);
        if (sim_.tick() % haptic_divider_ == 0) drive_hand();
        std::uint64_t length = std::min<std::uint64_t>(frames - i, sound_.size());
        length = std::min(length, haptic_divider_ - sim_.tick() % haptic_divider_);
        if (smoother_.active() > 0) length = 1;
        const std::size_t ran = sim_.run({sound_.data(), length});
        for (std::size_t k = 0; k < ran; ++k, ++i) {
            blown_up_ = !std::isfinite(sound_[k]);
            out[i] = limiter_.process(sound_[k]);
        }
    }
}

bool Instrument::continue_from(const Instrument& from) {
    if (from.model_id_ != model_id_ || from.blown_up_ || !sim_.continue_from(from.sim_, state_))
        return false;
    hand_ = from.hand_, drive_speed_ = from.drive_speed_;
    performer_.take_over(from.performer_);  // the notes held, the stroke, the vibrato
    smoother_ = from.smoother_;             // same slots: the glides go on
    bow_force_ = from.bow_force_, bow_speed_ = from.bow_speed_;
    damping_scale_ = from.damping_scale_;  // the state holds the scaled dampers already
    return true;
}

}  // namespace archet::lv2
