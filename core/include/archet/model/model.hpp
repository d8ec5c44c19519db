#pragma once
// The mass-interaction graph as the user edits it: MAT and LIA elements in SI units,
// rate levels, controls, probes and audio outputs. Plain data; `compile()` turns it into
// the flat arrays the simulation steps.

#include <optional>
#include <string>
#include <vector>
#include "archet/model/gesture.hpp"
#include "archet/model/parameter_name.hpp"

namespace archet {

/// A rate level: a fixed integer divider of the master clock (48 kHz / 16 = 3 kHz).
struct RateLevel {
    std::string id;
    int divider = 1;
};

enum class MatKind {
    Mass,        ///< punctual inertia
    Fixed,       ///< never moves
    Oscillator,  ///< inertia with a spring and damper to ground (the paper's bridges)
    Gesture,     ///< position imposed from a device axis; the force on it is fed back
    ModalPoint,  ///< no inertia of its own: x = Σ weight_k·x(mode_k); its force goes to the modes
};

enum class GestureAxis { Slide, Press };

struct Mat {
    std::string id;
    MatKind kind = MatKind::Mass;
    std::string rate = "audio";             ///< id of its rate level
    double mass = 0.0;                      ///< kg (Mass, Oscillator)
    double position = 0.0;                  ///< initial position, m; rest position of an oscillator
    double velocity = 0.0;                  ///< initial velocity, m/s (Mass, Oscillator)
    double stiffness = 0.0;                 ///< N/m to ground (Oscillator)
    double damping = 0.0;                   ///< N·s/m to ground (Oscillator)
    GestureAxis axis = GestureAxis::Slide;  ///< device axis (Gesture)
    double position_scale = 1.0;            ///< model metres per device metre (Gesture)
    double force_scale = 1.0;               ///< device newtons per model newton (Gesture)
    std::vector<std::string> modes;         ///< the modal oscillators it reads (ModalPoint)
    std::vector<double> weights;            ///< the mode shapes at this point (ModalPoint)
    std::optional<std::pair<double, double>> display;  ///< editor position
};

enum class LiaKind {
    Spring,        ///< F = K·(d − length)
    Damper,        ///< F = Z·Δd/T
    SpringDamper,  ///< F = K·(d − length) + Z·Δd/T
    Buffer,        ///< spring-damper acting only while the two MATs are in contact
    BowFriction,   ///< the quadripolar bow–string module (elastic buffer + friction)
    Finger,        ///< a stiff, damped stop from a point along a string to ground
};

/// A LIA. For two-point links `from`/`to` are the MATs and d = x(from) − x(to).
/// The bow module joins four MATs: `from` = bow mass on the sliding axis, `to` = bowed
/// string mass, `press` = bow mass on the pressure axis, `surface` = what it presses on.
/// A finger touches the string `along` (its MATs in order, from the bridge to the nut) at
/// `finger_position` (0 at the first, 1 at the last, continuous: between two MATs it acts on
/// both, weighted by the distance), with `pressure` × its stiffness and damping.
struct Lia {
    std::string id;
    LiaKind kind = LiaKind::Spring;
    std::string rate = "audio";
    std::string from;
    std::string to;
    double stiffness = 0.0;  ///< N/m (spring, buffer, bow's pressure buffer)
    double damping = 0.0;    ///< N·s/m
    double length = 0.0;     ///< rest length of springs; contact gap of buffers, m
    // BowFriction only:
    std::string press;
    std::string surface;
    double mu_static = 0.8;   ///< μs, friction coefficient when sticking
    double mu_dynamic = 0.3;  ///< μd, limit when sliding fast
    double v0 = 0.1;          ///< m/s, velocity scale of the decay from μs to μd
    // Finger only:
    std::vector<std::string> along;
    double finger_position = 1.0;  ///< 0…1 along `along`
    double pressure = 1.0;         ///< 0 (lifted) … 1 (pressed: full stiffness and damping)
    std::optional<std::pair<double, double>> display;

    // The bow module's and the buffer's names for the shared fields (the parameter table,
    // element_kinds.cpp, maps them the same way).
    const std::string& bow() const { return from; }
    const std::string& bowed_string() const { return to; }
    double buffer_stiffness() const { return stiffness; }
    double buffer_damping() const { return damping; }
    double gap() const { return length; }
};

/// The paper's parameter control function: drives one element parameter from a signal.
/// value = offset + gain · signal, clamped to [minimum, maximum].
struct Control {
    enum class Source { Envelope, Gesture, Position };
    std::string id;
    std::string rate = "audio";
    ParameterName target;  ///< the element parameter it drives
    Source source = Source::Envelope;
    std::vector<std::pair<double, double>> envelope;  ///< (time s, value) keyframes
    GestureAxis axis = GestureAxis::Slide;            ///< Source::Gesture
    std::string element;                              ///< Source::Position: a MAT
    double gain = 1.0;
    double offset = 0.0;
    double minimum = 0.0;
    double maximum = 0.0;
};

enum class ProbeKind {
    Position,       ///< m, of a MAT
    Velocity,       ///< m/s, of a MAT
    Force,          ///< N, force of the links on a MAT
    NormalForce,    ///< N, of a bow module
    FrictionForce,  ///< N, on the string, of a bow module
    SlipVelocity,   ///< m/s, bow minus string, of a bow module
    Energy,         ///< J, stored in the whole model
    PowerIn,        ///< W, delivered by the gesture points
};

struct Probe {
    std::string id;  ///< the CSV column name
    ProbeKind kind = ProbeKind::Position;
    std::string element;  ///< empty for Energy and PowerIn
};

/// Audio output: a MAT's signal times gain, summed over outputs, times the model's gain.
struct Output {
    enum class Signal { Position, Velocity, Force };
    std::string element;
    Signal signal = Signal::Force;
    double gain = 1.0;
};

struct Model {
    std::string name;
    std::string description;
    double sample_rate = 48000.0;  ///< master clock, Hz
    std::vector<RateLevel> rates{{"audio", 1}};
    std::vector<Mat> mats;
    std::vector<Lia> lias;
    std::vector<Control> controls;
    std::vector<Probe> probes;
    std::vector<Output> outputs;
    double output_gain = 1.0;
    std::optional<Gesture> gesture;  ///< played when no other gesture is given

    const Mat* find_mat(const std::string& id) const;
    const Lia* find_lia(const std::string& id) const;
    const RateLevel* find_rate(const std::string& id) const;
    Mat* find_mat(const std::string& id);
    Lia* find_lia(const std::string& id);
};

/// The model's first finger (a link of kind Finger), or null: what the pad's keys, OSC and
/// MIDI move.
const Lia* first_finger(const Model& model);
/// The model's first bow module (a link of kind BowFriction), or null: what the pad, OSC and
/// MIDI bow with, and what `bow.position` moves.
const Lia* first_bow(const Model& model);
Lia* first_bow(Model& model);

const char* to_string(MatKind);
const char* to_string(LiaKind);
const char* to_string(GestureAxis);
const char* to_string(ProbeKind);
const char* to_string(Output::Signal);
const char* to_string(Control::Source);

}  // namespace archet
