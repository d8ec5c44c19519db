#pragma once
// Two-parameter string losses inside the formalism: σ(ω) = σ0 + σ1·ω². σ0 comes from a damper
// from every string mass to its rest point (mass-proportional: every mode decays at σ0), σ1
// from the links' dampers (stiffness-proportional: a mode of angular frequency ω decays at
// σ1·ω²). Both are solved so that the built model's string modes, every other loss included
// (bridges, body), decay in the times asked for at two frequencies (physics.md §2.3).

#include <string>
#include <vector>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/model/model.hpp"

namespace archet {

struct StringLosses {
    double sigma0 = 0.0;  ///< 1/s, frequency-independent decay rate
    double sigma1 = 0.0;  ///< s, decay rate per ω²
};

/// 60 dB decay time (s) of a violin A string alone at `frequency` Hz, from the loss model of
/// Desvages (air damping, internal friction, viscoelasticity, after Valette 1995) with the
/// A string of Russo, Ducceschi & Bilbao's violin model; see physics.md §2.3.
double violin_string_t60(double frequency);

/// The violin A string's own decay rate (1/s) at `frequency` Hz (violin_string_t60's).
double violin_string_decay_rate(double frequency);

/// A decay asked for: `t60` seconds at `frequency` Hz, every loss included; 0: the violin A
/// string's own losses on top of the model's other losses. `option` names it in messages.
struct DecayTarget {
    double frequency = 0.0;
    double t60 = 0.0;
    std::string option;
};

/// The string inside a model: its masses and the links along it (ids).
struct StringElements {
    std::vector<std::string> masses, links;
};

/// The decay rate (1/s) the discrete scheme gives the string mode nearest `frequency`,
/// measured on the model's audio-rate linear part (first order in the damping).
struct ModeDecay {
    double frequency = 0.0;  ///< Hz, the mode's discrete frequency
    double rate = 0.0;       ///< 1/s, its amplitude decay rate
};

/// σ0 and σ1 that make the string modes nearest the two targets decay as asked, given every
/// other damper of `model` (whose string elements must carry no damping yet). Throws
/// InputError when that would need negative damping (the other losses alone decay faster, or
/// the high decay is not shorter than the low one allows).
StringLosses solve_string_losses(const Model& model, const StringElements& string,
                                 const DecayTarget& low, const DecayTarget& high);

/// Each string mass becomes an oscillator with no spring and damping 2σ0·m to its rest point;
/// each string link gets damping 2σ1·k.
void apply_string_losses(Model& model, const StringElements& string, const StringLosses& losses);

/// The discrete frequencies (Hz, ascending) of the undamped model's string modes: those whose
/// inertia is mostly in the string's masses (a bridge's or body's own modes are left out).
std::vector<double> string_mode_frequencies(const Model& model, const StringElements& string);

/// The discrete frequency (Hz) of the undamped model's string mode nearest `frequency` (0 when it
/// has none): string_mode_decay()'s, to the bit, from the eigenvalues alone and the shapes of the
/// modes nearest it, without the whole eigenbasis (what tuning a string to its pitch asks for).
/// The shapes come from another solve: a mode with half its inertia in the string to rounding,
/// or a string and a support mode within 1e-12 of the largest λ, could be told apart otherwise.
double string_mode_frequency(const Model& model, const StringElements& string, double frequency);

/// The decay of the string mode nearest `frequency` as the scheme runs it, every damper included
/// exactly: read from `modes`, the eigenvalues of its one-step update (discrete_modes() of the
/// model, a dense problem of twice its size that the caller has already solved).
ModeDecay exact_string_mode_decay(const Model& model, const StringElements& string,
                                  double frequency, const std::vector<DiscreteMode>& modes);

/// The decay of the string mode nearest `frequency` in `model` (as solve_string_losses sees it).
ModeDecay string_mode_decay(const Model& model, const StringElements& string, double frequency);

}  // namespace archet
