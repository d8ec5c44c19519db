#pragma once
// Which MATs are the string, for drawing its shape: those reached from a bowed mass through
// the model's links without crossing into a bow (its bow, pressure mass and surface), in model
// order; a bowed modal point (a string in modal form) reaches the points sharing its modes. A free
// mass added beside the string, or the bow and the hand, is not the string. Without a bow, every
// MAT but the gesture points.

#include <string>
#include <vector>

#include "archet/model/model.hpp"

namespace archet {

std::vector<std::string> string_points(const Model& model);

/// The MAT a bow module is centred on: its string end, or, when that end is a contact point
/// spread over neighbouring string masses (a bow with a width), the mass it weighs most.
std::string bowed_centre(const Model& model, const Lia& bow);

}  // namespace archet
