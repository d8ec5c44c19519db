#include "archet/analysis/modal_analysis_cache.hpp"

namespace archet {

ModalAnalysis ModalAnalysisCache::of(const Model& model) {
    LinearSystem system = sounding_part(model);
    std::optional<ModalSolve> solve;
    {
        const std::lock_guard lock(mutex_);
        if (last_ && identical(last_->first, system)) solve = last_->second;
    }
    if (!solve) {
        solve = solve_modes(system);  // outside the lock: seconds
        const std::lock_guard lock(mutex_);
        ++solves_;
        last_.emplace(system, *solve);
    }
    return class_modes(*solve, system, model);
}

std::size_t ModalAnalysisCache::solves() const {
    const std::lock_guard lock(mutex_);
    return solves_;
}

}  // namespace archet
