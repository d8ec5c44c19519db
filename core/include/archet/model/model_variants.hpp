#pragma once
// Named parameters of a bowed string that are not one element's: `string.damping` (the
// damping of every link of the string, N·s/m) and `bow.position` (β, where the bow meets the
// string). With ELEMENT.PARAM they are what `archet compare --vary` and the compare view
// vary. The string is the chain of masses and links the bow module rubs, without the bow's
// own masses and the hand's links.

#include <string>
#include <vector>

#include "archet/model/model.hpp"

namespace archet {

/// The string's links: joining two masses or oscillators, neither of them part of a bow
/// module or a gesture point. Empty for a modal string (it has no links).
std::vector<std::string> string_links(const Model& model);
/// The string's masses s1…sN in order, as the bowed-string builder names them.
std::vector<std::string> string_masses(const Model& model);

/// Sets a named parameter (string.damping, bow.position) or ELEMENT.PARAM; throws InputError
/// naming what is wrong. bow.position moves the bow module (and the probes that watched the
/// bowed mass) to the string mass nearest β·(N+1), and its drawing in the editor with it (its
/// masses and the hand's points that hold them).
void set_variant_parameter(Model& model, const std::string& name, double value);

/// "string.damping=0.001,0.01" → name and values; throws InputError.
std::pair<std::string, std::vector<double>> parse_variation(const std::string& text);

}  // namespace archet
