#pragma once
// Builds the bowed string: a chaplet of masses between two heavy damped bridges, tuned so its
// first mode is exactly the pitch under the discrete scheme, as many masses as the scheme
// allows at that pitch (full bandwidth) or the paper's 25–60; two-parameter losses; an
// optional body at the bridge; the bow module (two bow masses linked visco-elastically to two
// gesture points at the haptic rate); the friction module at the bowing point; and a steady
// stroke in the middle of the string's own Helmholtz band.

#include <atomic>
#include <string>

#include "archet/model/gesture.hpp"
#include "archet/model/model.hpp"

namespace archet {

/// Homogeneous: equal masses and links (inharmonic, the partials go flat). Harmonic: masses
/// and links from the inverse eigenvalue problem, first N partials on k·f0.
enum class Tuning { Homogeneous, Harmonic };

/// Chain: the chaplet of masses and links. Modal: its exact modal equivalent, one damped
/// oscillator per mode of the free chain, with a modal point (an equivalent MAT) at each of its
/// masses, so the same bridges and bow attach to it and its shape can be drawn.
enum class Structure { Chain, Modal };

struct BowedStringOptions {
    double pitch = 220.0;  ///< Hz, first mode of the string
    Tuning tuning = Tuning::Homogeneous;
    Structure structure = Structure::Chain;
    /// The paper's chaplets (25–60 masses, link damping alone, no body) for its figures.
    bool paper = false;
    int masses = 0;              ///< 0: full bandwidth (paper: the largest stable count up to 60)
    double bow_position = 0.12;  ///< β, bow distance from the bridge / string length
    /// Keep β even where the embedded stroke finds no Helmholtz band (else the bow may move to
    /// the next mass or two, where it finds one).
    bool bow_position_fixed = false;
    /// A finger ("finger") pressed on the string at `finger_position`, the share of the
    /// string between the bridge and the finger (1: at the nut, the open string).
    bool finger = false;
    double finger_position = 1.0;
    double string_damping = -1.0;  ///< N·s/m per string link, set by hand; < 0: from the decays
    /// s, 60 dB decay of the first mode, every loss included; 0: a violin A string's at the
    /// pitch (paper: 4 s, from link damping alone).
    double string_t60 = 0.0;
    double string_t60_high = 0.0;     ///< s, at string_t60_high_hz; 0: a violin A string's
    double string_t60_high_hz = 0.0;  ///< Hz; 0: 2000 Hz (twice the pitch above 1 kHz)
    std::string body = "violin";      ///< a body preset at the bridge, or "none" (string_body.hpp)
    /// The bow rubs one mass (the paper's). Else it rubs a contact point spread ¼, ½, ¼ over
    /// the bowed mass and its two neighbours, about a bow's hair width on a full string: the
    /// chain's shortest waves, which a real bow's width averages out, stay out of the friction.
    bool point_bow = false;
    double sample_rate = 48000.0;     ///< Hz, audio rate level
    int haptic_divider = 16;          ///< haptic rate = sample_rate / divider
    double tension = 57.1;            ///< N (violin A string)
    double linear_density = 0.72e-3;  ///< kg/m
    // Bridges: heavy damped oscillators to ground.
    double bridge_mass_ratio = 20.0;  ///< bridge mass / string mass
    double bridge_frequency = 20.0;   ///< Hz, bridge resonance
    double bridge_damping_ratio = 0.5;
    // Bow.
    double bow_mass = 0.05;            ///< kg, sliding axis
    double bow_stiffness = 1000.0;     ///< N/m, link to the device, sliding axis
    double bow_damping = 10.0;         ///< N·s/m
    double press_mass = 0.01;          ///< kg, pressure axis
    double press_stiffness = 100.0;    ///< N/m, link to the device, pressure axis
    double press_damping = 2.0;        ///< N·s/m
    double buffer_stiffness = 5000.0;  ///< N/m, bow–string contact
    double buffer_damping = 5.0;       ///< N·s/m
    double mu_s = 0.8, mu_d = 0.3, v0 = 0.1;
    /// Output to full scale; 0: so that the embedded stroke peaks at −6 dBFS (the paper's
    /// strings: 1.5 per newton of bridge force).
    double output_gain = 0.0;
    double stroke_speed = 0.1;  ///< m/s, the embedded stroke's bow speed
    bool with_gesture = true;   ///< embed a steady stroke in the middle of the Helmholtz band
};

/// The decay frequencies and times the options ask for, defaults filled in.
struct StringDecays {
    double low_hz = 0, low_t60 = 0, high_hz = 0, high_t60 = 0;
};
StringDecays string_decays(const BowedStringOptions& options);

/// Builds, tunes and validates the model; throws InputError with the reason when no
/// stable string exists for the options, and InputError "cancelled" once `*cancel` is set
/// (checked between the counts tried and between the strokes of the band search).
Model build_bowed_string(const BowedStringOptions& options,
                         const std::atomic<bool>* cancel = nullptr);

/// Adds the bow module to a model that has `string_mass` at the "audio" rate and a "haptic"
/// rate level: the two bow masses ("bow", "bow_press"), the surface, the two gesture points
/// ("hand_slide", "hand_press"), their links ("bow_hold", "press_hold") and "friction".
void add_bow_module(Model& model, const BowedStringOptions& options,
                    const std::string& string_mass);

/// Adds "finger", pressed at options.finger_position, along the string from "bridge" through
/// s1…sN to "nut" (the chain structure's).
void add_finger(Model& model, const BowedStringOptions& options, int masses);

/// The largest number of masses a homogeneous chain can have at this pitch and rate
/// (ω_max·T < 2), ignoring bridges and damping.
int max_stable_masses(double pitch, double sample_rate);

/// The largest number of masses of a harmonic chain: its N-th partial N·f0 below fs/2.
int max_harmonic_masses(double pitch, double sample_rate);

/// The full-bandwidth count: the most masses whose highest mode keeps `margin` of the
/// stability bound (λ·T² ≤ 4·(1 − margin)) in reserve.
int full_bandwidth_masses(double pitch, double sample_rate, Tuning tuning, double margin);

}  // namespace archet
