#pragma once
// The one table of element parameters. For every MAT and LIA kind: its numbers, in the
// order the model file writes them, each with its name (as in files, --set and controls),
// unit, range, whether the stability bound depends on it, its run-time role and the field
// of Mat or Lia that holds it. The file reader and writer, validation, --set, the inspector
// and the engine's name → slot resolution all read it: a new parameter is one row here
// plus its physics.

#include <optional>
#include <string>
#include <vector>

#include "archet/model/model.hpp"

namespace archet {

struct ParameterInfo {
    std::string name;
    std::string unit;
    double minimum;  ///< inclusive lower bound
    bool strictly_positive;
    double maximum;                   ///< inclusive upper bound (see input_limits.hpp)
    bool stability_relevant = false;  ///< the scheme's stability bound depends on it
};

/// What a parameter is to the physics: the compiled model finds its slot by role, so that
/// the names ("gap", "buffer_stiffness") stay in the table.
enum class ParameterRole {
    Position,  ///< initial (or fixed) position
    Velocity,  ///< initial velocity
    Mass,
    Stiffness,
    Damping,
    Length,  ///< rest length, or the contact gap of a buffer
    MuStatic,
    MuDynamic,
    V0,
    PositionScale,
    ForceScale,
    FingerPosition,  ///< where a finger touches its string, 0…1
    Pressure,        ///< how hard a finger presses, 0…1
};

/// One row of the table: a parameter of one kind of `Element` (Mat or Lia).
template <class Element>
struct ParameterEntry {
    ParameterInfo info;
    ParameterRole role;
    double Element::*field;
    std::optional<double> file_default;  ///< its value when a file leaves it out; none: required
};

using MatParameter = ParameterEntry<Mat>;
using LiaParameter = ParameterEntry<Lia>;

/// The parameters of a kind, in file order (empty for a modal point: its position follows
/// its modes).
const std::vector<MatParameter>& kind_parameters(MatKind kind);
/// Lia's fields are shared between kinds under other names: a buffer's "gap" is `length`, a
/// bow's "buffer_stiffness"/"buffer_damping" are `stiffness`/`damping` (and its bow and
/// string masses `from`/`to`). These rows are where that mapping is written down.
const std::vector<LiaParameter>& kind_parameters(LiaKind kind);

}  // namespace archet
