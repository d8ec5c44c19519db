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

// Before revision 6, the modal points nothing reads were stepped, and counted in the choice
// of taking the grounds in the chain loop (the decision made for the others' arithmetic).
bool grounds_choice_moved_in_revision_6(const CompiledLevel& level) {
    const bool counting_all = 2 * level.grounds.size() > static_cast<std::size_t>(level.size);
    return level.derived_after > 0 && grounds_in_chain_loop(level) != counting_all;
}

}  // namespace

SchemeChange scheme_change_since(const CompiledModel& model, int revision) {
    static_assert(kSchemeRevision == 6, "say here what the new revision changes");
    // 5: a finger or a bow moves the points reading the plain mass it pushes.
    if (revision < 5 && reads_a_point_stale_before_revision_5(model)) return SchemeChange::Fix;
    const auto any_level = [&](bool (*changed)(const CompiledLevel&)) {
        return std::any_of(model.levels.begin(), model.levels.end(), changed);
    };
    // 6: the grounds' choice counts only the MATs the chain loop steps.
    if (revision < 6 && any_level(grounds_choice_moved_in_revision_6))
        return SchemeChange::Rounding;
    // 4: the friction's reciprocals; a take re-renders with the divisions it was played with
    // (Simulation::compute_as_of()), so nothing differs.
    // 3: a modal point of more than eight terms sums them in interleaved partial sums.
    if (revision < 3 && any_level(has_long_modal_point)) return SchemeChange::Rounding;
    // 2: grounds folded into the chain loop's update.
    if (revision < 2 && any_level(grounds_in_chain_loop)) return SchemeChange::Rounding;
    return SchemeChange::None;
}

}  // namespace archet
