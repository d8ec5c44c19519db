#include "archet/physics/scheme_changes.hpp"

#include <algorithm>

#include "archet/common/scheme_revision.hpp"
#include "archet/physics/chain_kernel.hpp"

namespace archet {

bool computes_differently_since(const CompiledModel& model, int revision) {
    static_assert(kSchemeRevision == 2, "say here what the new revision changes");
    if (revision >= 2) return false;
    return std::any_of(model.levels.begin(), model.levels.end(),
                       [](const CompiledLevel& lv) { return grounds_in_chain_loop(lv); });
}

}  // namespace archet
