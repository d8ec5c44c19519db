#pragma once
// The stroke a new string carries: a steady stroke whose bow force sits in the middle of the
// string's own Helmholtz band, found by playing that stroke at forces log-spaced wide around
// Schelleng's lines and keeping those in steady Helmholtz motion from 1.5 s to the lift.

#include <atomic>

#include "archet/analysis/string_first_mode.hpp"
#include "archet/model/gesture.hpp"
#include "archet/model/model.hpp"

namespace archet {

struct HelmholtzBand {
    double low = 0.0, high = 0.0;  ///< N, the lowest and highest force of the band found
    double played = 0.0;           ///< N, the force in its middle (one of those played)
    double peak = 0.0;             ///< the output's peak over that stroke, at the model's gain
};

/// Steady strokes at `speed` m/s at `steps` log-spaced forces around Schelleng's lines; the
/// widest run of forces in steady Helmholtz motion. Throws InputError when none plays, and
/// InputError "cancelled" once `*cancel` is set (checked between strokes).
HelmholtzBand helmholtz_band(const Model& model, double speed, int steps = 17,
                             const std::atomic<bool>* cancel = nullptr);
/// The same with the string's first mode already analysed (string_first_mode(model)).
HelmholtzBand helmholtz_band(const Model& model, const StringFirstMode& first, double speed,
                             int steps = 17, const std::atomic<bool>* cancel = nullptr);

/// A steady stroke at `speed` with the band's middle force (`played`), 3 s long.
Gesture stroke_in_band(const Model& model, const HelmholtzBand& band, double speed);

}  // namespace archet
