#include "archet/physics/scheme_changes.hpp"

#include <algorithm>
#include <vector>

#include "archet/common/scheme_revision.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/modal_point_position.hpp"

namespace archet {

namespace {

bool has_long_modal_point(const CompiledLevel& level) {
    return std::any_of(level.modal_points.begin(), level.modal_points.end(),
                       [](const CompiledModalPoint& p) { return p.modes.size() > kModalSumLanes; });
}

// A finger that may touch a modal point and a plain mass another point reads (where it slides
// to does not matter: any two of its masses side by side).
bool has_finger_on_a_read_mass(const CompiledModel& model, const CompiledFinger& finger) {
    const CompiledLevel& lv = model.levels[finger.level];
    const std::vector<bool> is_mode = read_by_modal_points(lv);
    const auto modal = [&](int s) { return lv.modal_point_of[s] >= 0; };
    for (std::size_t i = 0; i + 1 < finger.along.size(); ++i) {
        const int a = finger.along[i], b = finger.along[i + 1];
        if ((modal(a) && !modal(b) && is_mode[b]) || (modal(b) && !modal(a) && is_mode[a]))
            return true;
    }
    return false;
}

}  // namespace

SchemeChange scheme_change_since(const CompiledModel& model, int revision) {
    static_assert(kSchemeRevision == 5, "say here what the new revision changes");
    // 5: a finger moves the points reading the plain mass it pushes.
    if (revision < 5 &&
        std::any_of(model.fingers.begin(), model.fingers.end(), [&](const CompiledFinger& finger) {
            return has_finger_on_a_read_mass(model, finger);
        }))
        return SchemeChange::Fix;
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
