#include "archet/model/model_parameters.hpp"

#include <cmath>
#include <cstdlib>

#include "archet/common/input_error.hpp"
#include "archet/common/input_limits.hpp"
#include "archet/common/number_text.hpp"
#include "archet/common/printable_text.hpp"

namespace archet {

namespace {

using namespace limits;

struct Field {
    ParameterInfo info;
    double* value;
};

std::vector<Field> mat_fields(Mat& m) {
    if (m.kind == MatKind::ModalPoint) return {};  // its position follows its modes
    std::vector<Field> f{{{"position", "m", -kPosition, false, kPosition}, &m.position}};
    switch (m.kind) {
        case MatKind::Mass:
            f.push_back({{"mass", "kg", 0.0, true, kMass}, &m.mass});
            f.push_back({{"velocity", "m/s", -kVelocity, false, kVelocity}, &m.velocity});
            break;
        case MatKind::Oscillator:
            f.push_back({{"mass", "kg", 0.0, true, kMass}, &m.mass});
            f.push_back({{"velocity", "m/s", -kVelocity, false, kVelocity}, &m.velocity});
            f.push_back({{"stiffness", "N/m", 0.0, false, kStiffness}, &m.stiffness});
            f.push_back({{"damping", "N·s/m", 0.0, false, kDamping}, &m.damping});
            break;
        case MatKind::Fixed:
            break;
        case MatKind::Gesture:
            f.push_back({{"position_scale", "m/m", -kScale, false, kScale}, &m.position_scale});
            f.push_back({{"force_scale", "N/N", -kScale, false, kScale}, &m.force_scale});
            break;
        case MatKind::ModalPoint:
            break;
    }
    return f;
}

std::vector<Field> lia_fields(Lia& l) {
    switch (l.kind) {
        case LiaKind::Spring:
            return {{{"stiffness", "N/m", 0.0, false, kStiffness}, &l.stiffness},
                    {{"length", "m", -kPosition, false, kPosition}, &l.length}};
        case LiaKind::Damper:
            return {{{"damping", "N·s/m", 0.0, false, kDamping}, &l.damping}};
        case LiaKind::SpringDamper:
            return {{{"stiffness", "N/m", 0.0, false, kStiffness}, &l.stiffness},
                    {{"damping", "N·s/m", 0.0, false, kDamping}, &l.damping},
                    {{"length", "m", -kPosition, false, kPosition}, &l.length}};
        case LiaKind::Buffer:
            return {{{"stiffness", "N/m", 0.0, false, kStiffness}, &l.stiffness},
                    {{"damping", "N·s/m", 0.0, false, kDamping}, &l.damping},
                    {{"gap", "m", -kPosition, false, kPosition}, &l.length}};
        case LiaKind::BowFriction:
            return {{{"buffer_stiffness", "N/m", 0.0, true, kStiffness}, &l.stiffness},
                    {{"buffer_damping", "N·s/m", 0.0, false, kDamping}, &l.damping},
                    {{"mu_s", "", 0.0, true, 10.0}, &l.mu_static},
                    {{"mu_d", "", 0.0, false, 10.0}, &l.mu_dynamic},
                    {{"v0", "m/s", 0.0, true, 100.0}, &l.v0}};
    }
    return {};
}

std::vector<Field> fields_of(Model& model, const std::string& element) {
    if (Mat* m = model.find_mat(element)) return mat_fields(*m);
    if (Lia* l = model.find_lia(element)) return lia_fields(*l);
    throw InputError(element, "no mass or link has this id");
}

Field& find_field(std::vector<Field>& fields, const std::string& element, const std::string& name) {
    for (auto& f : fields)
        if (f.info.name == name) return f;
    std::string names;
    for (const auto& f : fields) names += (names.empty() ? "" : ", ") + f.info.name;
    throw InputError(element,
                     "has no parameter " + quoted_text(name) + "; its parameters are: " + names);
}

}  // namespace

std::vector<ParameterInfo> element_parameters(const Model& model, const std::string& element) {
    std::vector<ParameterInfo> out;
    Model& m = const_cast<Model&>(model);  // fields_of only reads through these pointers here
    if (!m.find_mat(element) && !m.find_lia(element)) return out;
    for (const auto& f : fields_of(m, element)) out.push_back(f.info);
    return out;
}

double get_parameter(const Model& model, const std::string& element, const std::string& name) {
    Model& m = const_cast<Model&>(model);
    auto fields = fields_of(m, element);
    return *find_field(fields, element, name).value;
}

std::vector<ParameterValue> parameter_values(const Mat& mat) {
    std::vector<ParameterValue> out;
    for (const auto& f : mat_fields(const_cast<Mat&>(mat))) out.push_back({f.info, *f.value});
    return out;
}

std::vector<ParameterValue> parameter_values(const Lia& lia) {
    std::vector<ParameterValue> out;
    for (const auto& f : lia_fields(const_cast<Lia&>(lia))) out.push_back({f.info, *f.value});
    return out;
}

std::string range_problem(const ParameterInfo& info, double value) {
    const std::string unit = info.unit.empty() ? "" : " " + info.unit;
    if (!std::isfinite(value)) return info.name + " must be a finite number";
    if (value < info.minimum || (info.strictly_positive && value <= info.minimum))
        return info.name + " must be " + (info.strictly_positive ? "above " : "at least ") +
               format_number(info.minimum) + unit + " (is " + format_number(value) + ")";
    if (value > info.maximum)
        return info.name + " must be at most " + format_number(info.maximum) + unit + " (is " +
               format_number(value) + ")";
    return {};
}

void set_parameter(Model& model, const std::string& element, const std::string& name,
                   double value) {
    auto fields = fields_of(model, element);
    Field& f = find_field(fields, element, name);
    const std::string problem = range_problem(f.info, value);
    if (!problem.empty())
        throw InputError(element + "." + name, problem.substr(f.info.name.size() + 1));
    *f.value = value;
}

void apply_assignment(Model& model, const std::string& assignment) {
    const auto eq = assignment.find('=');
    const auto dot = assignment.rfind('.', eq);
    if (eq == std::string::npos || dot == std::string::npos || dot == 0 || dot + 1 >= eq)
        throw InputError("--set " + assignment, "expected ID.PARAM=VALUE, e.g. bow.mu_s=0.7");
    const std::string text = assignment.substr(eq + 1);
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0')
        throw InputError("--set " + assignment, quoted_text(text) + " is not a number");
    set_parameter(model, assignment.substr(0, dot), assignment.substr(dot + 1, eq - dot - 1),
                  value);
}

}  // namespace archet
