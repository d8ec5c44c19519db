#pragma once
// The options the commands that sweep a grid share (`archet map`, `archet attack`): a bound
// on the work, the threads, the shard of a sweep spread over jobs, and the files written.

#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>

#include "archet/common/input_limits.hpp"

namespace archet::cli {

struct SweepOptions {
    std::size_t max_points = limits::kMapPoints;
    int jobs = 0;
    std::string shard = "0/1", output, png;

    /// Refuses (InputError naming `option`) a grid of `a_steps` × `b_steps` points over
    /// --max-points.
    void check_size(int a_steps, int b_steps, const std::string& option) const;
    /// The shard "I/N" as (I, N); InputError "--shard" when it does not read so.
    std::pair<int, int> shard_of() const;
    int threads() const;  ///< --jobs, or every core
};

/// Adds --max-points (`grid`: what its points are, e.g. "force steps × position steps"),
/// --jobs, --shard, -o (`output`: what the CSV holds) and --png (`png`: what it draws).
void add_sweep_options(CLI::App& command, SweepOptions& options, const std::string& grid,
                       const std::string& output, const std::string& png);

}  // namespace archet::cli
