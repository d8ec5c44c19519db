#include "archet/analysis/modal_analysis_cache.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>

namespace archet {

namespace {

// The same points reading the same DOFs with weights of the same bits (a −0 is not a +0).
bool same_reads(const ModalPointReads& a, const ModalPointReads& b) {
    auto same_weight = [](const std::pair<int, double>& x, const std::pair<int, double>& y) {
        return x.first == y.first &&
               std::bit_cast<std::uint64_t>(x.second) == std::bit_cast<std::uint64_t>(y.second);
    };
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [&](const auto& x, const auto& y) {
        return x.first == y.first && std::equal(x.second.begin(), x.second.end(), y.second.begin(),
                                                y.second.end(), same_weight);
    });
}

}  // namespace

bool ModalAnalysisCache::Inputs::same_as(const Inputs& other) const {
    return identical(system, other.system) && supports == other.supports &&
           same_reads(points, other.points);
}

ModalAnalysis ModalAnalysisCache::of(const Model& model) {
    Inputs inputs;
    inputs.system = sounding_part(model);
    check_analysable(inputs.system);  // first, as analyse_modes() refuses it
    inputs.supports = support_dofs(inputs.system, model);
    inputs.points = modal_point_reads(inputs.system, model);
    {
        const std::lock_guard lock(mutex_);
        if (last_ && last_->first.same_as(inputs)) return last_->second;
    }
    ModalAnalysis modes = analyse_modes(inputs.system, model);  // outside the lock: seconds
    const std::lock_guard lock(mutex_);
    ++solves_;
    last_.emplace(std::move(inputs), modes);
    return modes;
}

std::size_t ModalAnalysisCache::solves() const {
    const std::lock_guard lock(mutex_);
    return solves_;
}

}  // namespace archet
