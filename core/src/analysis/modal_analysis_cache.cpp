#include "archet/analysis/modal_analysis_cache.hpp"

namespace archet {

ModalAnalysis ModalAnalysisCache::of(const Model& model) {
    const LinearSystem system = sounding_part(model);
    return class_modes(solves_.of(system, solve_modes), system, model);
}

std::size_t ModalAnalysisCache::solves() const {
    return solves_.solves();
}

}  // namespace archet
