#pragma once
// What the LV2 plugin plays: one compiled model with its MIDI performer, the hand the
// performer's bow drive slides on at the gesture points' rate, the parameter glides and the
// string's damping scale. Built off the audio thread (the plugin's worker, or instantiate);
// then everything it does in run() is real-time safe: no allocation, no lock, no I/O.

#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "archet/midi/midi_performer.hpp"
#include "archet/model/model.hpp"
#include "archet/output_limiter.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/parameter_smoother.hpp"
#include "archet/physics/simulation.hpp"

namespace archet::lv2 {

class Instrument {
  public:
    /// Compiles `model` at `sample_rate` with the bow at β = `bow_position` (0: the model's
    /// own), its bowed chain loop in `build`, else in the one fastest_chain_build() times (a
    /// bow moved along the string keeps the model's). Throws InputError when it cannot be played
    /// from MIDI (no bow, unstable).
    Instrument(Model model, double sample_rate, double bow_position,
               std::optional<ChainBuild> build = std::nullopt);

    // ---- real-time ----
    void receive(const midi::MidiMessage& message) { performer_.receive(message); }
    /// The control ports: bow force (N at velocity 127), speed (m/s), the string's damping
    /// as a factor of the model's.
    void set_controls(double bow_force, double bow_speed, double damping_scale);
    /// Renders `frames` samples (the performer's round first).
    void render(float* out, std::uint32_t frames);
    /// Takes over `from`'s motion and parameters when it plays the same model (only the bow's
    /// contact moved): no restart, no click. False when the two do not match.
    bool continue_from(const Instrument& from);
    /// The simulation stopped being finite: silent until replaced.
    bool blown_up() const { return blown_up_; }
    double bow_position() const { return bow_position_; }
    ChainBuild chain_build() const { return sim_.chain_build(); }
    /// What it plays, for its probes (tests read the bow's slip velocity).
    const Simulation& simulation() const { return sim_; }
    /// A bow position MIDI asked for since the last call (CC 4), or 0.
    double take_bow_request() { return std::exchange(bow_request_, 0.0); }
    std::uint64_t model_id() const { return model_id_; }
    void set_model_id(std::uint64_t id) { model_id_ = id; }

  private:
    void apply_round(double seconds);
    void drive_hand();

    Model model_;  ///< as played: the bow where asked, checked
    Simulation sim_;
    midi::MidiPerformer performer_;
    ParameterSmoother smoother_;
    OutputLimiter limiter_;
    /// The performer's parameters: the finger's position and pressure slots (−1 kind: none).
    std::vector<ParameterSlot> finger_slots_;
    struct Damping {
        ParameterSlot slot;
        double base;  ///< the model's own value
    };
    std::vector<Damping> damping_;  ///< every damper of the string
    double damping_scale_ = 1, bow_force_ = -1, bow_speed_ = -1;
    double largest_damping_scale_ = 1;  ///< the most the model stays stable with
    GestureSample hand_{};
    double drive_speed_ = 0;
    std::uint64_t haptic_divider_ = 1;
    double haptic_dt_ = 0;
    int glide_samples_ = 480;
    double bow_position_ = 0, bow_request_ = 0;
    std::uint64_t model_id_ = 0;
    std::vector<double> state_;       ///< room for continue_from()'s hand-over
    std::array<double, 64> sound_{};  ///< a run's sound (render())
    bool blown_up_ = false;
};

}  // namespace archet::lv2
