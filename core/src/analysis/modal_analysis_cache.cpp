#include "archet/analysis/modal_analysis_cache.hpp"

#include <algorithm>
#include <iterator>
#include <optional>

namespace archet {

ModalAnalysis ModalAnalysisCache::of(const Model& model) {
    LinearSystem system = sounding_part(model);
    std::optional<ModalSolve> solve;
    {
        const std::lock_guard lock(mutex_);
        const auto found = std::find_if(kept_.begin(), kept_.end(), [&](const auto& kept) {
            return identical(kept.first, system);
        });
        if (found != kept_.end()) {
            solve = found->second;
            std::rotate(kept_.begin(), found, std::next(found));  // now the most recent
        }
    }
    if (!solve) {
        solve = solve_modes(system);  // outside the lock: seconds
        const std::lock_guard lock(mutex_);
        ++solves_;
        kept_.emplace_front(system, *solve);
        if (kept_.size() > kKept) kept_.pop_back();
    }
    return class_modes(*solve, system, model);
}

std::size_t ModalAnalysisCache::solves() const {
    const std::lock_guard lock(mutex_);
    return solves_;
}

}  // namespace archet
