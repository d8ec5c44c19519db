#pragma once
// Element parameters by name ("s5.mass", "friction.mu_s"), for `--set`, controls, and the
// inspector, looked up in the table of element kinds (element_kinds.hpp).

#include <string>
#include <vector>

#include "archet/model/element_kinds.hpp"
#include "archet/model/model.hpp"
#include "archet/model/parameter_name.hpp"

namespace archet {

/// What is wrong with `value` for `info` ("must be at most 100 m/s (is 1e+300)"), or "" when
/// it is finite and in range.
std::string range_problem(const ParameterInfo& info, double value);

/// The parameters an element of the model has (empty when no such element).
std::vector<ParameterInfo> element_parameters(const Model& model, const std::string& element);

/// The table's row for a parameter with its role; throws InputError naming the element and
/// its valid names.
ParameterInfo parameter_info(const Model& model, const ParameterName& name);
ParameterRole parameter_role(const Model& model, const ParameterName& name);

double get_parameter(const Model& model, const ParameterName& name);

/// Sets a parameter of the model; throws InputError naming the element and the valid names
/// or range (the model is unchanged then).
void set_parameter(Model& model, const ParameterName& name, double value);

/// The field holding a parameter, for values already validated where they were entered (a
/// model kept in step with one that checked them); throws only for an unknown name.
double& parameter_field(Model& model, const ParameterName& name);

/// Parses "ID.PARAM=VALUE" and applies it.
void apply_assignment(Model& model, const std::string& assignment);

}  // namespace archet
