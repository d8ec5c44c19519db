#pragma once
// How far one parameter of one element can go before the explicit scheme at its rate level
// turns unstable: the inspector's live margin per element. Stiffness and damping can grow up
// to a limit, a mass can shrink down to one.

#include <optional>
#include <string>

#include "archet/model/model.hpp"
#include "archet/model/parameter_name.hpp"

namespace archet {

struct StabilityLimit {
    double value = 0;    ///< the limit, in the parameter's units
    bool upper = true;   ///< the parameter must stay below it (else above it)
    double current = 0;  ///< where the parameter is now
};

/// The limit of ELEMENT.PARAMETER (a stability-relevant one of the parameter table: stiffness,
/// damping or mass; relative precision 1e-6), or nothing when that parameter cannot make the
/// scheme unstable (or the model is unstable already).
/// Probes the values in `model` itself and puts the parameter back: no copy of the model.
std::optional<StabilityLimit> stability_limit(Model& model, const ParameterName& name);
/// The same on a copy of `model`.
std::optional<StabilityLimit> stability_limit(const Model& model, const ParameterName& name);

}  // namespace archet
