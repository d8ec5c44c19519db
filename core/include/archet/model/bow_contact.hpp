#pragma once
// The contact point of a bow with a width: ¼, ½, ¼ of the string at the bowed mass and its two
// neighbours. On a chain it reads the three masses; on a string in modal form it is a modal
// point of its own whose weights mix those of the three points there, mode by mode, in this
// order (so that a contact moved along the string has the bits of one built there).

#include <cstddef>
#include <vector>

#include "archet/model/model.hpp"

namespace archet {

/// The id the bowed-string builder gives a contact point.
inline constexpr const char* kBowContact = "bow_contact";

inline double contact_weight(double before, double at, double after) {
    return 0.25 * before + 0.5 * at + 0.25 * after;
}

/// Whether modal point `p` reads the modes `contact` reads, weight for weight: a contact mixes
/// only such points.
inline bool mixes_into(const Mat& p, const Mat& contact) {
    return p.kind == MatKind::ModalPoint && p.modes == contact.modes &&
           p.weights.size() == contact.weights.size() && p.weights.size() == p.modes.size();
}

/// The weights of a contact point centred on modal point `at`, between `before` and `after`
/// (three points on the same modes, mixes_into() the contact).
inline std::vector<double> contact_weights(const Mat& before, const Mat& at, const Mat& after) {
    std::vector<double> weights(at.weights.size());
    for (std::size_t k = 0; k < weights.size(); ++k)
        weights[k] = contact_weight(before.weights[k], at.weights[k], after.weights[k]);
    return weights;
}

}  // namespace archet
