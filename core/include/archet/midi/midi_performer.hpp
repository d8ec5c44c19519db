#pragma once
// A player who reads MIDI: notes stop the string with the model's finger and bow it, the pitch
// wheel and vibrato move the finger, controllers set the bow's force and speed and any
// parameter (midi_mapping.hpp). Fed the messages as they come and asked, at each round, how the
// bow moves (a speed and a press, which the real-time side slides on smoothly) and which
// parameters change, as the pad and OSC play a model, so takes record and re-render MIDI like
// them. Real-time safe once built: receive() and advance() neither allocate nor lock, so the
// engine's control thread and an LV2 plugin's run() both play through it.
//
// Monophonic, as a bowed string is: the newest held note sounds; releasing it returns to the
// one held before (legato, the bow keeps its direction); releasing the last lifts the bow. Each
// new stroke bows the other way from the last, as a player changes bow.

#include <array>
#include <optional>
#include <span>
#include <string>

#include "archet/midi/midi_mapping.hpp"
#include "archet/midi/midi_message.hpp"
#include "archet/model/model.hpp"
#include "archet/model/parameter_name.hpp"

namespace archet::midi {

/// What the performer needs of the model it plays.
struct PerformedModel {
    /// The finger's id, empty without one: notes then bow the open string at any pitch.
    std::string finger;
    double open_string_hz = 0;     ///< the string's first mode (> 0 when there is a finger)
    double newtons_per_press = 1;  ///< bow force per metre of the hand's press axis
};

/// A parameter a round sets: the finger's position or pressure, or a control route's parameter.
struct ParameterRequest {
    enum class What { FingerPosition, FingerPressure, BowPosition, Route };
    What what = What::FingerPosition;
    int route = -1;  ///< Route: the index in the mapping's controls
    double value = 0;
};

/// A message the performer could not play.
struct Refusal {
    enum class Why { OutOfReach, NoFinger };
    Why why = Why::OutOfReach;
    int number = 0;  ///< the note, or the controller
};

/// The model's: its first finger, the open string's first mode, the bow's force per metre of
/// press. Throws InputError when MIDI cannot bow it (no bow module, no string mode).
PerformedModel performed_model(const Model& model);

class MidiPerformer {
  public:
    MidiPerformer(MidiMapping mapping, PerformedModel model);

    /// Takes a message; one that cannot be played (a note below the open string) is refused
    /// in the next round.
    void receive(const MidiMessage& message);
    /// What a controller of `target` sets (bow force or speed, vibrato), as a controller would:
    /// an LV2 plugin's control ports.
    void set(MidiTarget target, double value);
    /// Plays on where `other` was (held notes, stroke, controllers, vibrato, what it last
    /// sent): a performer of the same model with its bow moved. Copies no map: real-time safe.
    void take_over(const MidiPerformer& other);
    /// The bow force of velocity 1 and 127 from now on (N).
    void set_velocity_force(double minimum, double maximum) {
        mapping_.velocity_force_min = minimum, mapping_.velocity_force_max = maximum;
    }

    struct Round {
        bool bow_changed = false;  ///< the two below differ from the last round's
        double slide_speed = 0;    ///< m/s, signed by the stroke's direction; 0: not bowing
        double press = 0;          ///< m on the hand's press axis; 0: lifted
        /// The newest value of each parameter asked for this round.
        std::array<ParameterRequest, kChannelPressure + 3> requests{};
        std::size_t request_count = 0;
        std::array<Refusal, 8> refusals{};
        std::size_t refusal_count = 0, refusals_lost = 0;
        std::span<const ParameterRequest> parameters() const {
            return {requests.data(), request_count};
        }
        std::span<const Refusal> refused() const { return {refusals.data(), refusal_count}; }
    };
    /// Moves the vibrato on by `seconds` (the time since the last round).
    Round advance(double seconds);

    /// The parameter a request sets, by name (allocates: for messages and the engine).
    ParameterName parameter_of(const ParameterRequest& request) const;
    /// A sentence for a refusal (allocates).
    std::string describe(const Refusal& refusal) const;

    /// Where the finger stops the string for `note` (the sounding share, 0 … 1), or nothing
    /// out of its reach.
    std::optional<double> finger_position(int note) const;
    bool bowing() const { return held_count_ > 0; }

  private:
    bool heard(const MidiMessage& m) const;
    void control(int controller, int value);
    void note_on(int note, int velocity);
    void note_off(int note);
    void release(int note);
    double force() const;
    void request(ParameterRequest r);
    void refuse(Refusal r);

    MidiMapping mapping_;
    PerformedModel model_;
    double slide_speed_ = 0, press_ = 0;  ///< as last sent
    std::array<int, 128> held_{};         ///< notes held, oldest first
    std::size_t held_count_ = 0;
    double direction_ = -1;                              ///< of the last stroke; the first goes +1
    double velocity_force_ = 0, controlled_force_ = -1;  ///< N; −1: no controller has set it
    double speed_;
    double vibrato_depth_ = 0, vibrato_rate_ = 5, vibrato_phase_ = 0;
    double bend_ = 0;         ///< semitones
    double finger_set_ = -1;  ///< the finger position last sent (−1: none yet)
    int sounding_ = -1;       ///< the note the finger stops, held or last released (−1: none)
    Round pending_;
};

}  // namespace archet::midi
