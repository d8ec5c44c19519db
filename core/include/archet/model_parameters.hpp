#pragma once
// Element parameters by name ("s5.mass", "bow.mu_s"), for `--set`, controls, and the
// inspector: each with its unit and the range it may take.

#include <string>
#include <vector>

#include "archet/model.hpp"

namespace archet {

struct ParameterInfo {
    std::string name;
    std::string unit;
    double minimum;  ///< inclusive lower bound
    bool strictly_positive;
};

/// The parameters an element of the model has (empty when no such element).
std::vector<ParameterInfo> element_parameters(const Model& model, const std::string& element);

double get_parameter(const Model& model, const std::string& element, const std::string& name);

/// Sets a parameter; throws InputError naming the element and the valid names or range.
void set_parameter(Model& model, const std::string& element, const std::string& name, double value);

/// Parses "ID.PARAM=VALUE" and applies it.
void apply_assignment(Model& model, const std::string& assignment);

}  // namespace archet
