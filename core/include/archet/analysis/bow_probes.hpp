#pragma once
// A model whose only probes are its bow's: what an analysis reads at every tick of a stroke
// (slip velocity, normal force), read through run() with the rest of the tick (run_ticks()).

#include <initializer_list>

#include "archet/model/model.hpp"

namespace archet {

/// Replaces `model`'s probes with its bow's `kinds`, in that order (each named as its kind);
/// false, and `model` left as it was, when it has no bow.
bool read_bow_only(Model& model, std::initializer_list<ProbeKind> kinds);

}  // namespace archet
