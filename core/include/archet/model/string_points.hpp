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

/// Which of a string's `points` (string_points()) a drawing of at most `most` of them shows, as
/// indices into them: all of them when they fit, else `most` spread evenly from the first to
/// the last, so that the drawing still runs from the bridge to the nut.
std::vector<std::size_t> drawn_points(std::size_t points, std::size_t most);

/// Where a bow can stand on a string as the bowed-string builder names it: its masses s1…sN,
/// or, for a string in modal form, its points there.
std::vector<std::string> bow_stations(const Model& model);

/// The MAT a bow module is centred on: its string end, or, when that end is a contact point (a
/// bow with a width, bow_contact.hpp), the mass it weighs most or the modal point it mixes
/// with its neighbours.
std::string bowed_centre(const Model& model, const Lia& bow);

}  // namespace archet
