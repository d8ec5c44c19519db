#pragma once
// Which MATs are the string, for drawing its shape: those reached from a bowed mass through
// the model's links without crossing into a bow (its bow, pressure mass and surface), in model
// order. A free mass added beside the string, or the bow and the hand, is not the string.
// Without a bow, every MAT but the gesture points.

#include <string>
#include <vector>

#include "archet/model/model.hpp"

namespace archet {

std::vector<std::string> string_points(const Model& model);

}  // namespace archet
