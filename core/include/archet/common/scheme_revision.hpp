#pragma once
// Which revision of the scheme's arithmetic this Archet computes. Under one revision the same
// model, gesture and starting state give the same bytes on every machine and build; a new
// revision changes the order or form of the arithmetic (never the physics), so what an older
// one rendered comes out again with the same physics but not to the byte, unless
// Simulation::compute_as_of() can still compute as it did. A take records the revision it was
// played with, and a re-render that may differ says so.
//   1  up to December 2026
//   2  a level that takes its grounds in the chain loop folds them into the update's
//      coefficients (docs/physics.md, The scheme)
//   3  a modal point of more than eight terms sums them in eight interleaved partial sums
//      (physics/modal_point_position.hpp)
//   4  the friction solve, and the slip velocity it reports, multiply by the reciprocals of T
//      and of the masses' response where they divided (physics/bow_solve.cpp); told to compute
//      as of an older revision (Simulation::compute_as_of()), the solve divides
//   5  a fix, not arithmetic: a finger or a bow that pushes a plain mass a modal point reads
//      moves that point before anything reads it (Simulation::push_pair()); before,
//      a bow could read such a point, and a step end with it, where the push had not moved it
//   6  a level's grounds go into the chain loop when most of the MATs it steps have one: the
//      modal points that nothing reads, which the step now leaves out (derived points,
//      physics/compiled_model.hpp), are no longer counted

namespace archet {

constexpr int kSchemeRevision = 6;

}  // namespace archet
