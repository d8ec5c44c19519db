#pragma once
// The string's first partial as analyse_modes() finds it, bit for bit, for what needs only the
// pitch and its decay (playability and attack maps, comparisons, bowing reports): the roots
// come from the same eigenvalue solve without its eigenvectors (about half its cost), and only
// the modes from the lowest up to the first partial have their shape solved, to tell a mode
// of the supports from the string's.

#include "archet/analysis/discrete_modes.hpp"
#include "archet/model/linear_system.hpp"
#include "archet/model/model.hpp"

namespace archet {

struct ModalAnalysis;

struct StringFirstMode {
    double frequency = 0;  ///< f1, Hz; 0 when no mode is the string's
    double t60 = 0;        ///< s, its decay by 60 dB (0 when there is no f1)
};

/// What analyse_modes(model) gives as its fundamental and the t60 of its partial 1, with the
/// same bits; it throws what analyse_modes() throws. The roots are the same; where the modes up
/// to f1 could be classed otherwise (two at one frequency, a mode's energy split within 1e-9 of
/// half in the supports, a shape the solve cannot find) and on a model with a finger, it is
/// analyse_modes() itself.
StringFirstMode string_first_mode(const Model& model);
StringFirstMode string_first_mode(const LinearSystem& system, const Model& model);
/// The same from the roots of the model's sounding part (sounding_part(model)), solved already.
StringFirstMode string_first_mode(const UpdateRoots& roots, const Model& model);

/// The same read from a whole analysis.
StringFirstMode string_first_mode(const ModalAnalysis& modes);

}  // namespace archet
