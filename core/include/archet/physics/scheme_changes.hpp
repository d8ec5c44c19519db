#pragma once
// What changed between revisions of the scheme's arithmetic (common/scheme_revision.hpp), for a
// given model: a take played under an older revision re-renders to the byte unless it did.

#include "archet/physics/compiled_model.hpp"

namespace archet {

/// Whether `model` computes other bits under this Archet's revision than under `revision`
/// (1 … kSchemeRevision): from revision 2 on, a level whose chain loop takes its grounds folds
/// them into the update's coefficients; from revision 3 on, a modal point of more than eight
/// terms sums them in interleaved partial sums. Revision 4's friction is not among them: a
/// simulation told to compute as of an older revision (Simulation::compute_as_of()) divides as
/// that revision did.
bool computes_differently_since(const CompiledModel& model, int revision);

}  // namespace archet
