#include "archet/builders/string_body.hpp"

#include <cmath>
#include <numbers>

#include "archet/common/input_error.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/model/stability.hpp"

namespace archet {

namespace {

// Turns the body's velocities (m/s) into an output comparable to the bridge force (N) it
// replaces: a characteristic impedance, N·s/m. Chosen so that the default bowed note, with the
// builder's output gain, peaks in the same −12…−3 dBFS range as the bridge-force output
// (string_body_test checks it).
constexpr double kRadiationImpedance = 36.0;

std::string preset_names() {
    std::string names;
    for (const auto& p : body_presets()) names += p.name + ", ";
    return names + "none";
}

}  // namespace

const std::vector<BodyPreset>& body_presets() {
    // The violin's four "signature modes", the body resonances below 600 Hz that dominate its
    // bridge admittance and its low-frequency radiation, and the "bridge hill" near 2–3 kHz as
    // two modes of ζ = 0.1 (one mode would need ζ ≈ 0.25, where the scheme's backward-difference
    // damper is 20 % off the continuous admittance at 48 kHz). Without the hill the string's
    // upper partials hardly lose energy at the bridge, and a point-like bow finds almost no
    // Helmholtz band (docs/physics.md, Body).
    // Frequencies: Woodhouse, Euphonics §5.3 (numbers from Bissinger's modal surveys). The
    // source gives no damping or effective masses: ζ and m are CHOSEN, not measured (Q ≈ 25–33
    // for the four modes; masses so that the admittance peaks 1/(2ζmω) are 0.1–0.3 s/kg).
    // Radiation: A0 (the air breathing through the f-holes), B1−
    // and B1+ radiate well; CBR (a rotation of the centre bouts) hardly at all: weights chosen.
    static const std::vector<BodyPreset> presets{
        {"violin",
         "violin body: signature modes A0, CBR, B1-, B1+",
         "Mode frequencies from J. Woodhouse, Euphonics: The Science of Musical Instruments, "
         "section 5.3 \"Signature modes and formants\", https://euphonics.org/"
         "5-3-signature-modes-and-formants/ (after G. Bissinger, \"Structural acoustics of good "
         "and bad violins\", J. Acoust. Soc. Am. 124(3):1764-1773, 2008): A0 272 Hz, CBR 407 Hz, "
         "B1- 462 Hz, B1+ 551 Hz. Damping ratios, effective masses "
         "and radiation weights are chosen, not from the source (docs/physics.md, Body).",
         {
             {272.0, 0.020, 0.120, 1.0},  // A0: f-hole air resonance
             {407.0, 0.020, 0.090, 0.2},  // CBR: centre-bout rotation, a weak radiator
             {462.0, 0.015, 0.036, 1.0},  // B1−: first corpus bending mode
             {551.0, 0.015, 0.030, 1.0},  // B1+: second corpus bending mode
             // The "bridge hill": the bridge rocking on the body, a broad hump of admittance
             // around 2–3 kHz. Two damped modes, ζ = 0.1, peaks 0.3 s/kg: CHOSEN.
             {2200.0, 0.10, 0.0012, 0.5},
             {2900.0, 0.10, 0.00091, 0.5},
         }},
    };
    return presets;
}

const BodyPreset& find_body_preset(const std::string& name) {
    for (const auto& p : body_presets())
        if (p.name == name) return p;
    throw InputError("--body", "unknown body \"" + name + "\"; known bodies: " + preset_names());
}

void attach_body(Model& model, const BodyPreset& body, const std::string& bridge_id) {
    Mat* bridge = model.find_mat(bridge_id);
    if (!bridge || (bridge->kind != MatKind::Oscillator && bridge->kind != MatKind::Mass))
        throw InputError("--body", "the body attaches to a bridge mass or oscillator called \"" +
                                       bridge_id + "\", and this model has none");
    if (body.modes.empty()) throw InputError("--body", "body \"" + body.name + "\" has no modes");
    // The bridge point reads every body mode with weight 1: a unit force on it drives each
    // mode with unit modal force, so its admittance is exactly the modal sum, with each
    // effective mass as measured at the bridge. It has no inertia of its own, and the body's
    // ground springs replace the heavy bridge's: the measured admittance already includes the
    // real bridge, so keeping the old mass would count it twice and add a 20 Hz mode no
    // violin has. It keeps its id, so the string's link, the probes and outputs still find it.
    const std::string rate = bridge->rate;
    const auto display = bridge->display;
    bridge->kind = MatKind::ModalPoint;
    bridge->mass = bridge->stiffness = bridge->damping = bridge->velocity = 0.0;
    bridge->modes.clear(), bridge->weights.clear();
    model.outputs.clear();
    std::vector<Mat> modes;
    for (std::size_t k = 0; k < body.modes.size(); ++k) {
        const BodyMode& b = body.modes[k];
        const double omega = 2.0 * std::numbers::pi * b.frequency;
        Mat m;
        m.id = "body" + std::to_string(k + 1), m.kind = MatKind::Oscillator, m.rate = rate;
        m.mass = b.effective_mass;
        m.stiffness = b.effective_mass * omega * omega;
        m.damping = 2.0 * b.damping_ratio * b.effective_mass * omega;
        const double x = display ? display->first : 0.0, y = display ? display->second : 0.0;
        m.display = {{x - 80.0, y + 40.0 * static_cast<double>(k)}};
        bridge->modes.push_back(m.id), bridge->weights.push_back(1.0);
        // What the body radiates: each mode's velocity times how well it radiates.
        if (b.radiation != 0.0)
            model.outputs.push_back(
                {m.id, Output::Signal::Velocity, b.radiation * kRadiationImpedance});
        modes.push_back(std::move(m));
    }
    model.mats.insert(model.mats.end(), modes.begin(), modes.end());
    model.description += " Body: " + body.instrument + " (" + std::to_string(body.modes.size()) +
                         " modes), sound radiated by the body.";
    for (const auto& report : analyse_stability(model))
        if (!report.stable())
            throw InputError("--body", "body \"" + body.name + "\" makes the " + report.rate +
                                           " level unstable (largest normalised eigenvalue " +
                                           std::to_string(report.largest_eigenvalue) + " of 4)");
    validate_model(model);
}

}  // namespace archet
