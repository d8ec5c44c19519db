#pragma once
// An instrument body for the bowed string: the paper's bridges "can be linked to other parts of
// the instrument". The body is a modal structure, one damped oscillator per body mode; the
// string's bridge becomes a modal point reading them all, so that the driving-point admittance
// at the bridge is the modal sum Y(ω) = Σ jω / (m_k·(ω_k² − ω² + 2jζ_k·ω_k·ω)). The sound is
// what the body radiates: the modes' velocities weighted by how well each one radiates.

#include <string>
#include <vector>

#include "archet/model/model.hpp"

namespace archet {

/// One body mode as seen from the bridge.
struct BodyMode {
    double frequency;       ///< Hz
    double damping_ratio;   ///< ζ (Q = 1 / 2ζ)
    double effective_mass;  ///< kg, the mode's mass at the bridge (its admittance peak 1/(2ζmω))
    double radiation;       ///< relative weight of its velocity in the radiated sound
};

struct BodyPreset {
    std::string name;        ///< what --body takes
    std::string instrument;  ///< what it models, in a few words
    std::string source;      ///< the published measurements it comes from, and what was chosen
    std::vector<BodyMode> modes;
};

/// The presets, in the order the user sees them.
const std::vector<BodyPreset>& body_presets();

/// The preset called `name`. Throws InputError("--body", …) naming the presets and `none`.
const BodyPreset& find_body_preset(const std::string& name);

/// Couples the body to the string at `bridge_id` (an oscillator or mass MAT at the audio rate):
/// adds one oscillator MAT per mode ("body1", …), turns the bridge into a modal point reading
/// them with weight 1 (it keeps its id, its links, probes and outputs), and makes the body's
/// radiation the model's outputs. Throws InputError("--body", …) when the bridge is missing or
/// the result is not stable; validates the model.
void attach_body(Model& model, const BodyPreset& body, const std::string& bridge_id = "bridge");

}  // namespace archet
