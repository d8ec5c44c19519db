#pragma once
// What changed between revisions of the scheme's arithmetic (common/scheme_revision.hpp), for a
// given model: a take played under an older revision re-renders to the byte unless it did.

#include "archet/physics/compiled_model.hpp"

namespace archet {

/// How `model` computes otherwise under this Archet's revision than under `revision`
/// (1 … kSchemeRevision), or none. From revision 2 on, a level whose chain loop takes its
/// grounds folds them into the update's coefficients; from revision 3 on, a modal point of more
/// than eight terms sums them in interleaved partial sums (both rounding: the same physics).
/// From revision 5 on, a finger or a bow that pushes a plain mass a modal point reads moves
/// that point before anything reads it (a fix). From revision 6 on, the choice of taking the
/// grounds in the chain loop leaves out the modal points nothing reads (rounding, where that
/// turns the choice). Revision 4's friction is not among them: a
/// simulation told to compute as of an older revision (Simulation::compute_as_of()) divides as
/// that revision did.
enum class SchemeChange { None, Rounding, Fix };
SchemeChange scheme_change_since(const CompiledModel& model, int revision);

}  // namespace archet
