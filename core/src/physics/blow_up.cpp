#include "archet/physics/blow_up.hpp"

#include <cmath>

#include "archet/common/input_error.hpp"
#include "archet/common/number_text.hpp"
#include "archet/common/printable_text.hpp"

namespace archet {

std::optional<std::string> find_blown_up_element(const Simulation& sim) {
    const CompiledModel& model = sim.model();
    for (const CompiledLevel& level : model.levels) {
        const double* x = level.x();
        for (int i = 1; i <= level.size; ++i) {  // MATs 1 … size (0 is padding)
            if (std::isfinite(x[i])) continue;
            const int element =
                i < static_cast<int>(level.element_of.size()) ? level.element_of[i] : -1;
            const std::string name = element >= 0
                                         ? "mass " + quoted_text(model.source.mats[element].id)
                                         : "a mass of rate level " + quoted_text(level.id);
            return name + " (position " + format_number(x[i]) + ")";
        }
    }
    return std::nullopt;
}

bool simulation_is_finite(const Simulation& sim) {
    if (!std::isfinite(sim.output())) return false;
    for (std::size_t p = 0; p < sim.probe_count(); ++p)
        if (!std::isfinite(sim.probe(p))) return false;
    return !find_blown_up_element(sim);
}

void throw_blow_up(const Simulation& sim) {
    const auto element = find_blown_up_element(sim);
    const std::string what =
        element ? *element + " was the first to blow up" : "the output or a probe overflowed";
    throw InputError("model", "the simulation stopped being finite at t = " +
                                  format_number(sim.time()) + " s: " + what +
                                  "; nothing was written. Check the gesture and the initial "
                                  "positions and velocities, or lower output_gain");
}

}  // namespace archet
