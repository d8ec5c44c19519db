#pragma once
// Outputs that are the velocities of a run of MATs at audio rate, in storage order: a body's
// modes radiating, as the shipped strings sound. The bowed chain's loop divides them a vector
// at a time (core/src/physics/velocity_run_output.hpp) where output() divides one at a time.

#include "archet/physics/compiled_model.hpp"

namespace archet {

/// Outputs such a run holds at most: the loop keeps their gains in its frame.
inline constexpr int kMostVelocityOutputs = 8;

struct VelocityRun {
    int first = 0;  ///< storage index of the first output's MAT
    int count = 0;  ///< 0: the outputs are not such a run
    double dt = 1;
    double output_gain = 1;
    double gain[kMostVelocityOutputs] = {};
};

/// The run `model`'s outputs make at audio rate, or a run of count 0.
inline VelocityRun find_velocity_run(const CompiledModel& model) {
    VelocityRun run;
    const int n = static_cast<int>(model.outputs.size());
    if (n == 0 || n > kMostVelocityOutputs || model.levels.empty()) return run;
    const CompiledOutput& first = model.outputs[0];
    for (int k = 0; k < n; ++k) {
        const CompiledOutput& o = model.outputs[k];
        if (o.signal != Output::Signal::Velocity || o.mat.level != 0 ||
            o.mat.index != first.mat.index + k)
            return run;
        run.gain[k] = o.gain;
    }
    run.first = first.mat.index, run.count = n;
    run.dt = model.levels[0].dt, run.output_gain = model.output_gain;
    return run;
}

}  // namespace archet
