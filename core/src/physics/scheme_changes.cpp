#include "archet/physics/scheme_changes.hpp"

#include <algorithm>

#include "archet/common/scheme_revision.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/modal_point_position.hpp"

namespace archet {

namespace {

bool has_long_modal_point(const CompiledLevel& level) {
    return std::any_of(level.modal_points.begin(), level.modal_points.end(),
                       [](const CompiledModalPoint& p) { return p.modes.size() > kModalSumLanes; });
}

}  // namespace

bool computes_differently_since(const CompiledModel& model, int revision) {
    static_assert(kSchemeRevision == 4, "say here what the new revision changes");
    // 4: the friction's reciprocals; a take re-renders with the divisions it was played with
    // (Simulation::compute_as_of()), so nothing differs.
    const auto any_level = [&](bool (*changed)(const CompiledLevel&)) {
        return std::any_of(model.levels.begin(), model.levels.end(), changed);
    };
    // 3: a modal point of more than eight terms sums them in interleaved partial sums.
    if (revision < 3 && any_level(has_long_modal_point)) return true;
    // 2: grounds folded into the chain loop's update.
    return revision < 2 && any_level(grounds_in_chain_loop);
}

}  // namespace archet
