#pragma once
// A second bow module for a built bowed string: the shapes that one bow does not cover (a level
// that solves two bows, the bowed chain loop's refusal) need one.

#include <string>

#include "archet/model/model.hpp"

namespace archet::test {

/// Adds "friction2", a copy of the model's "friction" with bow and pressure masses of its own
/// ("bow2" and "bow_press2", copies of "bow" and "bow_press", held by nothing), rubbing `mat`.
inline void add_second_bow(Model& model, const std::string& mat) {
    Lia second = *model.find_lia("friction");
    for (const char* mass : {"bow", "bow_press"}) {
        Mat copy = *model.find_mat(mass);
        copy.id += "2";
        model.mats.push_back(copy);
    }
    second.id = "friction2", second.from = "bow2", second.press = "bow_press2", second.to = mat;
    model.lias.push_back(second);
}

}  // namespace archet::test
