#pragma once
// Everything a model must satisfy before it is compiled: ids, references, ranges, rate
// levels, and the scheme's stability bound at every rate level.

#include <string>
#include <vector>

#include "archet/model/model.hpp"
#include "archet/model/parameter_name.hpp"

namespace archet {

struct ModelProblem {
    std::string where;    ///< the element at fault, e.g. `link "l3"`
    std::string message;  ///< what is wrong and what to change
};

/// All problems found; structural ones first. The stability bound is checked only when
/// the structure is sound.
std::vector<ModelProblem> find_model_problems(const Model& model);

/// Throws InputError for the first problem.
void validate_model(const Model& model);

/// Sets one parameter and validates the whole model with it (its range, then the stability
/// bound), in place: no copy of the model. When the value is refused the model is left as it
/// was and InputError says why.
void set_parameter_validated(Model& model, const ParameterName& name, double value);

}  // namespace archet
