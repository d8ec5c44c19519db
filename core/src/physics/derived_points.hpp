#pragma once
// The modal points that nothing in the step reads (a modal string's points between its ends and
// its bow, there to draw its shape): compile() lays them out last, where the chain loop stops,
// and leaves them out of the step (CompiledLevel::derived_points). Private to the physics
// sources.

#include <vector>

#include "archet/model/model.hpp"

namespace archet {

/// Which of the model's MATs (by index) are modal points that nothing in the step reads: no
/// link, bow or finger touches them, and no control, probe or output reads them.
std::vector<bool> find_derived_points(const Model& model);

/// `order` (model MAT indices, as the level is laid out) with the derived points moved to its
/// end, `chain_link_after` (the chain link after each) moved with it.
void hold_derived_points_last(std::vector<int>& order, std::vector<int>& chain_link_after,
                              const std::vector<bool>& derived);

}  // namespace archet
