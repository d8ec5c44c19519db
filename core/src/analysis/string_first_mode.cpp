#include "archet/analysis/string_first_mode.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <vector>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/mode_shape.hpp"

namespace archet {

namespace {

using Complex = std::complex<double>;

struct Root {
    Complex z;
    double frequency, t60;
};

// Where the fast path could class a mode otherwise than the whole analysis: two roots at one
// frequency (one shape found for both, and their order is the sort's), or a mode's energy
// split within rounding of half and half.
bool ties(const Root& a, const Root& b) {
    return std::abs(a.frequency - b.frequency) <= 1e-12 * std::abs(b.frequency);
}
bool near_half(const EnergySplit& e) {
    return std::abs(e.in_supports - 0.5 * e.kinetic) <= 1e-9 * e.kinetic;
}

}  // namespace

StringFirstMode string_first_mode(const Model& model) {
    return string_first_mode(sounding_part(model), model);
}

StringFirstMode string_first_mode(const LinearSystem& sys, const Model& model) {
    if (!sys.fingers.empty()) return string_first_mode(analyse_modes_densely(sys, model));
    check_analysable(sys);  // before a solve that an unanalysable system could make endless
    return string_first_mode(update_roots(sys), model);
}

StringFirstMode string_first_mode(const UpdateRoots& update, const Model& model) {
    const LinearSystem& sys = update.system;
    auto whole_analysis = [&] { return string_first_mode(analyse_modes_densely(sys, model)); };
    if (!sys.fingers.empty()) return whole_analysis();  // their correction is in U alone
    check_analysable(sys);
    const double dt = sys.dt;
    // Without eigenvectors Eigen runs the same reduction and QR steps on the Schur form and
    // only leaves out accumulating their basis: the roots are analyse_modes()' to the bit.
    if (!update.converged) return whole_analysis();  // which says so
    std::vector<Root> roots;
    for (const Complex& z : update.roots) {
        if (z.imag() <= 0.0) continue;  // as analyse_modes(): one of each pair, no real roots
        roots.push_back({z, root_frequency(z, dt), root_t60(z, dt)});
    }
    std::sort(roots.begin(), roots.end(),
              [](const auto& a, const auto& b) { return a.frequency < b.frequency; });
    const std::vector<bool> is_support = support_dofs(sys, model);
    for (std::size_t r = 0; r < roots.size(); ++r) {
        if (r + 1 < roots.size() && ties(roots[r], roots[r + 1])) return whole_analysis();
        const std::optional<std::vector<Complex>> shape = mode_shape(sys, roots[r].z);
        if (!shape) return whole_analysis();
        const EnergySplit energy = energy_split(sys, is_support, *shape);
        if (!energy.finite() || near_half(energy)) return whole_analysis();
        if (!energy.support()) return {roots[r].frequency, roots[r].t60};
    }
    return {};
}

StringFirstMode string_first_mode(const ModalAnalysis& modes) {
    StringFirstMode first;
    for (const ModeInfo& mode : modes.modes)
        if (mode.partial == 1) first = {modes.fundamental, mode.t60};
    return first;
}

}  // namespace archet
