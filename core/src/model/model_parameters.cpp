#include "archet/model/model_parameters.hpp"

#include <cmath>
#include <cstdlib>

#include "archet/common/input_error.hpp"
#include "archet/common/number_text.hpp"
#include "archet/common/printable_text.hpp"

namespace archet {

namespace {

// A parameter of one element: its row in the table and the field that holds it.
struct Found {
    const ParameterInfo& info;
    ParameterRole role;
    double& value;
};

template <class Element>
Found find_row(Element& element, const ParameterName& name) {
    const auto& rows = kind_parameters(element.kind);
    for (const auto& r : rows)
        if (r.info.name == name.parameter) return {r.info, r.role, element.*r.field};
    std::string names;
    for (const auto& r : rows) names += (names.empty() ? "" : ", ") + r.info.name;
    throw InputError(name.element, "has no parameter " + quoted_text(name.parameter) +
                                       "; its parameters are: " + names);
}

Found find_parameter(Model& model, const ParameterName& name) {
    if (Mat* m = model.find_mat(name.element)) return find_row(*m, name);
    if (Lia* l = model.find_lia(name.element)) return find_row(*l, name);
    throw InputError(name.element, "no mass or link has this id");
}

// Only read through: the lookup is shared with the writers.
Found find_parameter(const Model& model, const ParameterName& name) {
    return find_parameter(const_cast<Model&>(model), name);
}

}  // namespace

std::vector<ParameterInfo> element_parameters(const Model& model, const std::string& element) {
    std::vector<ParameterInfo> out;
    auto add = [&](const auto& rows) {
        for (const auto& r : rows) out.push_back(r.info);
    };
    if (const Mat* m = model.find_mat(element)) add(kind_parameters(m->kind));
    if (const Lia* l = model.find_lia(element)) add(kind_parameters(l->kind));
    return out;
}

ParameterInfo parameter_info(const Model& model, const ParameterName& name) {
    return find_parameter(model, name).info;
}

ParameterRole parameter_role(const Model& model, const ParameterName& name) {
    return find_parameter(model, name).role;
}

double get_parameter(const Model& model, const ParameterName& name) {
    return find_parameter(model, name).value;
}

std::string range_problem(const ParameterInfo& info, double value) {
    if (!std::isfinite(value)) return info.name + " must be a finite number";
    const bool low = value < info.minimum || (info.strictly_positive && value <= info.minimum);
    if (!low && !(value > info.maximum)) return {};  // the common case: nothing to spell
    const std::string unit = info.unit.empty() ? "" : " " + info.unit;
    if (low)
        return info.name + " must be " + (info.strictly_positive ? "above " : "at least ") +
               format_number(info.minimum) + unit + " (is " + format_number(value) + ")";
    return info.name + " must be at most " + format_number(info.maximum) + unit + " (is " +
           format_number(value) + ")";
}

void set_parameter(Model& model, const ParameterName& name, double value) {
    const Found f = find_parameter(model, name);
    const std::string problem = range_problem(f.info, value);
    if (!problem.empty()) throw InputError(name.text(), problem.substr(f.info.name.size() + 1));
    f.value = value;
}

double& parameter_field(Model& model, const ParameterName& name) {
    return find_parameter(model, name).value;
}

void apply_assignment(Model& model, const std::string& assignment) {
    const auto eq = assignment.find('=');
    if (eq == std::string::npos)
        throw InputError("--set " + assignment, "expected ID.PARAM=VALUE, e.g. friction.mu_s=0.7");
    const auto name = ParameterName::parse(assignment.substr(0, eq), "--set " + assignment);
    const std::string text = assignment.substr(eq + 1);
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0')
        throw InputError("--set " + assignment, quoted_text(text) + " is not a number");
    set_parameter(model, name, value);
}

}  // namespace archet
