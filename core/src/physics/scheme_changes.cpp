#include "archet/physics/scheme_changes.hpp"

#include <algorithm>
#include <cstddef>

#include "archet/common/scheme_revision.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/modal_point_position.hpp"

namespace archet {

namespace {

bool has_long_modal_point(const CompiledLevel& level) {
    return std::any_of(level.modal_points.begin(), level.modal_points.end(),
                       [](const CompiledModalPoint& p) { return p.modes.size() > kModalSumLanes; });
}

// Where revision 4 left a modal point behind its modes when it was read: a finger whose touch
// may push a modal point and then a plain mass a point reads (`along` in that order, wherever it
// slides), and a bow on a plain mass a point reads (its force on it moved no point; over-flagged
// where a push on a modal point after it moved them all).
bool reads_a_point_stale_before_revision_5(const CompiledModel& model) {
    for (const CompiledFinger& finger : model.fingers) {
        const CompiledLevel& lv = model.levels[finger.level];
        for (std::size_t i = 0; i + 1 < finger.along.size(); ++i)
            if (lv.modal_point_of[finger.along[i]] >= 0 && lv.read_by_point[finger.along[i + 1]])
                return true;
    }
    for (const CompiledLevel& lv : model.levels)
        for (int b : lv.bows)
            if (lv.read_by_point[model.bows[b].bow] || lv.read_by_point[model.bows[b].string])
                return true;
    return false;
}

}  // namespace

SchemeChange scheme_change_since(const CompiledModel& model, int revision) {
    static_assert(kSchemeRevision == 5, "say here what the new revision changes");
    // 5: a finger or a bow moves the points reading the plain mass it pushes.
    if (revision < 5 && reads_a_point_stale_before_revision_5(model)) return SchemeChange::Fix;
    // 4: the friction's reciprocals; a take re-renders with the divisions it was played with
    // (Simulation::compute_as_of()), so nothing differs.
    const auto any_level = [&](bool (*changed)(const CompiledLevel&)) {
        return std::any_of(model.levels.begin(), model.levels.end(), changed);
    };
    // 3: a modal point of more than eight terms sums them in interleaved partial sums.
    if (revision < 3 && any_level(has_long_modal_point)) return SchemeChange::Rounding;
    // 2: grounds folded into the chain loop's update.
    if (revision < 2 && any_level(grounds_in_chain_loop)) return SchemeChange::Rounding;
    return SchemeChange::None;
}

}  // namespace archet
