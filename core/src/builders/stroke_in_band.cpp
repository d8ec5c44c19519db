#include "archet/builders/stroke_in_band.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "archet/analysis/bow_probes.hpp"
#include "archet/analysis/bowing_analysis.hpp"
#include "archet/analysis/playability.hpp"
#include "archet/analysis/string_first_mode.hpp"
#include "archet/common/denormal_guard.hpp"
#include "archet/common/input_error.hpp"
#include "archet/common/parallel_for.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/physics/run_ticks.hpp"
#include "archet/physics/simulation.hpp"

namespace archet {

namespace {

constexpr double kStrokeSeconds = 3.0;          // as long as the shipped steady-bow gesture
constexpr double kLift = kStrokeSeconds - 0.4;  // steady_bow_gesture lifts 0.4 s before its end
constexpr double kSteadyFrom = 1.5;             // s: Helmholtz motion from here to the lift
// Schelleng's lines come from an idealised string: look well beyond them on both sides.
constexpr double kBelowMinimum = 0.25, kAboveMaximum = 3.0;

// The stroke at `force`, played to its end: in steady Helmholtz motion by kSteadyFrom, every
// period after its onset one slip within 1 % of the steady period until the lift, as
// `archet bowing` judges it (analyse_attack), and Helmholtz motion from kSteadyFrom to the lift.
// `model` reads its bow's slip velocity and normal force (read_bow_only()).
bool plays_helmholtz(const Model& model, double pitch, double speed, double force, double& peak) {
    const Gesture stroke =
        steady_bow_gesture(speed, force / force_for_press(model, 1.0), kStrokeSeconds);
    Simulation sim(compile(model));
    sim.set_gesture_track(&stroke);
    const DenormalGuard no_denormals;
    const double fs = sim.sample_rate();
    const auto end = static_cast<std::size_t>(kStrokeSeconds * fs);
    std::vector<double> slip, normal;
    slip.reserve(end), normal.reserve(end);
    run_ticks(sim, end, [&](std::size_t, double sample, const double* row) {
        slip.push_back(row[0]), normal.push_back(row[1]);
        peak = std::max(peak, std::abs(sample));
        return true;
    });
    const AttackAnalysis attack = analyse_attack(slip, normal, fs, pitch);
    if (!attack.reached() || attack.helmholtz > kSteadyFrom) return false;
    const auto from = static_cast<std::size_t>(kSteadyFrom * fs);
    const auto lift = static_cast<std::size_t>((kLift - 0.05) * fs);
    return analyse_bowing(slip, fs, pitch, from, lift).helmholtz();
}

}  // namespace

HelmholtzBand helmholtz_band(const Model& model, double speed, int steps,
                             const std::atomic<bool>* cancel) {
    bow_position(model);  // a model without a bow is told so before its modes are analysed
    return helmholtz_band(model, string_first_mode(model), speed, steps, cancel);
}

HelmholtzBand helmholtz_band(const Model& model, const StringFirstMode& first, double speed,
                             int steps, const std::atomic<bool>* cancel) {
    const double beta = bow_position(model);
    const SchellengBounds lines = schelleng_lines(model, first).at(beta, speed);
    const double pitch = first.frequency;
    // Without Schelleng's lines (a modal string has no links to read its impedance from), the
    // range a violinist's bow covers.
    const bool lined = lines.minimum > 0 && lines.maximum > lines.minimum;
    const double low = lined ? std::max(1e-4, kBelowMinimum * lines.minimum) : 3e-3;
    const double high = lined ? std::max(low * 100, kAboveMaximum * lines.maximum) : 3.0;
    Model probed = model;
    if (!read_bow_only(probed, {ProbeKind::SlipVelocity, ProbeKind::NormalForce}))
        throw InputError(model.name, "has no bow to find a Helmholtz band with");
    std::vector<double> forces(steps), peaks(steps, 0.0);
    std::vector<char> plays(steps, 0);  // not vector<bool>: each stroke writes its own byte
    for (int i = 0; i < steps; ++i) forces[i] = low * std::pow(high / low, i / (steps - 1.0));
    // The strokes are independent: played side by side on every core.
    const bool finished = parallel_for(
        forces.size(), hardware_jobs(),
        [&](std::size_t i) {
            plays[i] = plays_helmholtz(probed, pitch, speed, forces[i], peaks[i]);
        },
        cancel);
    if (!finished) throw InputError(model.name, "cancelled");
    // The widest run of consecutive forces that play; its middle force was played too.
    HelmholtzBand best;
    int best_length = 0;
    for (int i = 0; i < steps;) {
        int j = i;
        while (j < steps && plays[j]) ++j;
        if (j - i > best_length) {
            best_length = j - i;
            best = {forces[i], forces[j - 1], forces[(i + j - 1) / 2], peaks[(i + j - 1) / 2]};
        }
        i = j + 1;
    }
    if (best_length == 0) {
        std::ostringstream message;
        message << "no steady stroke at " << speed << " m/s plays Helmholtz motion between " << low
                << " and " << high << " N; try another bow position or string";
        throw InputError("--bow-position", message.str());
    }
    return best;
}

Gesture stroke_in_band(const Model& model, const HelmholtzBand& band, double speed) {
    return steady_bow_gesture(speed, band.played / force_for_press(model, 1.0), kStrokeSeconds);
}

}  // namespace archet
