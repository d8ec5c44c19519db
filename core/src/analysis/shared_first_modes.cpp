#include "archet/analysis/shared_first_modes.hpp"

#include <exception>

#include "archet/analysis/modal_analysis.hpp"

namespace archet {

StringFirstMode SharedFirstModes::of(const Model& model) {
    LinearSystem system = sounding_part(model);
    // As string_first_mode(system, model) goes: a finger's correction needs the whole analysis,
    // and a system that cannot be analysed is refused before a solve.
    if (!system.fingers.empty()) return string_first_mode(system, model);
    check_analysable(system);
    std::promise<UpdateRoots> solving;
    std::shared_future<UpdateRoots> roots;
    bool mine = false;
    {
        const std::lock_guard lock(mutex_);
        for (const auto& [solved, its_roots] : solved_)
            if (identical(solved, system)) {
                roots = its_roots;
                break;
            }
        if (!roots.valid()) {
            roots = solving.get_future().share();
            solved_.emplace_back(system, roots);
            mine = true;
        }
    }
    if (mine) {  // solved outside the lock: the others ask on, or wait for this one
        try {
            solving.set_value(update_roots(std::move(system)));
        } catch (...) {
            solving.set_exception(std::current_exception());
        }
    }
    return string_first_mode(roots.get(), model);
}

std::size_t SharedFirstModes::solves() const {
    const std::lock_guard lock(mutex_);
    return solved_.size();
}

}  // namespace archet
