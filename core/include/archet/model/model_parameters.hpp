#pragma once
// Element parameters by name ("s5.mass", "bow.mu_s"), for `--set`, controls, and the
// inspector: each with its unit and the range it may take.

#include <string>
#include <vector>

#include "archet/model/model.hpp"

namespace archet {

struct ParameterInfo {
    std::string name;
    std::string unit;
    double minimum;  ///< inclusive lower bound
    bool strictly_positive;
    double maximum;  ///< inclusive upper bound (see input_limits.hpp)
};

/// A parameter with the value it has in one element.
struct ParameterValue {
    ParameterInfo info;
    double value;
};

/// The parameters of one mass or link with their values (no lookup by id: for validation).
std::vector<ParameterValue> parameter_values(const Mat& mat);
std::vector<ParameterValue> parameter_values(const Lia& lia);

/// What is wrong with `value` for `info` ("must be at most 100 m/s (is 1e+300)"), or "" when
/// it is finite and in range.
std::string range_problem(const ParameterInfo& info, double value);

/// The parameters an element of the model has (empty when no such element).
std::vector<ParameterInfo> element_parameters(const Model& model, const std::string& element);

double get_parameter(const Model& model, const std::string& element, const std::string& name);

/// Sets a parameter; throws InputError naming the element and the valid names or range.
void set_parameter(Model& model, const std::string& element, const std::string& name, double value);

/// Parses "ID.PARAM=VALUE" and applies it.
void apply_assignment(Model& model, const std::string& assignment);

}  // namespace archet
