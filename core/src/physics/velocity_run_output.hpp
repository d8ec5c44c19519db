#pragma once
// The sound of a run of velocity outputs (archet/physics/velocity_run.hpp): output() for that
// one shape, its divisions a vector at a time. Each lane divides, and takes its gain, as
// output() does for that output alone, and the products are added in output()'s order, so the
// bits are output()'s; a vector of divisions costs less than one division an output. Private to
// the physics sources: the bowed chain's loop finds the run once per block.

#include "archet/physics/compiled_model.hpp"
#include "archet/physics/velocity_run.hpp"
#include "double_vectors.hpp"

namespace archet::velocity_run_output {

// Whole vectors of W doubles (W divides kMostVelocityOutputs) from the run's first MAT read up
// to index first + 7 ≤ size + 7: inside the storage (size + 2) and its read-ahead.
static_assert(CompiledLevel::kReadAhead >= kMostVelocityOutputs - 2);

/// output() after a step of the audio level, from its new positions `x` and its previous `xp`.
template <int W>
[[gnu::always_inline]] inline double sound(const VelocityRun& run, const double* x,
                                           const double* xp) {
    using V = double_vectors::Doubles<W>;
    static_assert(kMostVelocityOutputs % W == 0, "whole vectors of gains and terms");
    double term[kMostVelocityOutputs];
    for (int k = 0; k < run.count; k += W) {
        const V velocity = (double_vectors::load<V>(x + run.first + k) -
                            double_vectors::load<V>(xp + run.first + k)) /
                           run.dt;
        double_vectors::store(term + k, double_vectors::load<V>(run.gain + k) * velocity);
    }
    double sum = 0;
    for (int k = 0; k < run.count; ++k) sum += term[k];
    return run.output_gain * sum;
}

}  // namespace archet::velocity_run_output
