#include "archet/analysis/shared_first_modes.hpp"

#include "archet/analysis/modal_analysis.hpp"

namespace archet {

StringFirstMode SharedFirstModes::of(const Model& model) {
    const LinearSystem system = sounding_part(model);
    // As string_first_mode(system, model) goes: a finger's correction needs the whole analysis,
    // and a system that cannot be analysed is refused before a solve.
    if (!system.fingers.empty()) return string_first_mode(system, model);
    check_analysable(system);
    return string_first_mode(roots_.of(system, update_roots), model);
}

}  // namespace archet
