#pragma once
// The sound of a model whose outputs are the velocities of a run of MATs at audio rate, in
// storage order (a body's modes radiating, as the shipped strings sound): output() for that
// one shape, its divisions a vector at a time. Each lane divides, and takes its gain, as
// output() does for that output alone, and the products are added in output()'s order, so the
// bits are output()'s; a division a vector costs less than one per output. Private to the
// physics sources: the bowed chain's loop finds the run once per block.

#include <cstddef>

#include "archet/physics/compiled_model.hpp"
#include "double_vectors.hpp"

namespace archet::velocity_run_output {

/// Outputs a run holds at most: the loop keeps their gains in its frame.
inline constexpr int kMostOutputs = 8;

struct Run {
    int first = 0;  ///< storage index of the first output's MAT
    int count = 0;  ///< 0: the outputs are not such a run
    double dt = 1;
    double output_gain = 1;
    double gain[kMostOutputs] = {};
};

/// The run `model`'s outputs make at audio rate, or a run of count 0.
inline Run find_run(const CompiledModel& model) {
    Run run;
    const int n = static_cast<int>(model.outputs.size());
    if (n == 0 || n > kMostOutputs || model.levels.empty()) return run;
    const CompiledOutput& first = model.outputs[0];
    for (int k = 0; k < n; ++k) {
        const CompiledOutput& o = model.outputs[k];
        if (o.signal != Output::Signal::Velocity || o.mat.level != 0 ||
            o.mat.index != first.mat.index + k)
            return run;
        run.gain[k] = o.gain;
    }
    // sound() reads whole vectors, up to index first + 2·kMostOutputs − 2 ≤ size + 14: inside
    // the storage (size + 2) and its read-ahead.
    static_assert(CompiledLevel::kReadAhead >= 2 * kMostOutputs - 3);
    const CompiledLevel& audio = model.levels[0];
    run.first = first.mat.index, run.count = n;
    run.dt = audio.dt, run.output_gain = model.output_gain;
    return run;
}

/// output() after a step of the audio level, from its new positions `x` and its previous `xp`.
template <int W>
[[gnu::always_inline]] inline double sound(const Run& run, const double* x, const double* xp) {
    using V = double_vectors::Doubles<W>;
    double term[kMostOutputs];
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
