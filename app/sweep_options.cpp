#include "sweep_options.hpp"

#include <cstdio>

#include "archet/common/input_error.hpp"
#include "archet/common/parallel_for.hpp"

namespace archet::cli {

void SweepOptions::check_size(int a_steps, int b_steps, const std::string& option) const {
    if (static_cast<double>(a_steps) * b_steps > static_cast<double>(max_points))
        throw InputError(option, std::to_string(a_steps) + " × " + std::to_string(b_steps) +
                                     " points is more than --max-points " +
                                     std::to_string(max_points) +
                                     "; use fewer STEPS, or raise --max-points and share the "
                                     "work with --shard");
}

std::pair<int, int> SweepOptions::shard_of() const {
    int index = 0, count = 1;
    if (std::sscanf(shard.c_str(), "%d/%d", &index, &count) != 2)
        throw InputError("--shard", "expected I/N, e.g. 3/16");
    return {index, count};
}

int SweepOptions::threads() const {
    return jobs > 0 ? jobs : hardware_jobs();
}

void add_sweep_options(CLI::App& command, SweepOptions& options, const std::string& grid,
                       const std::string& output, const std::string& png) {
    command
        .add_option("--max-points", options.max_points,
                    "Largest grid accepted (" + grid + "), a bound on the work")
        ->capture_default_str();
    command.add_option("--jobs", options.jobs, "Threads (0: every core)")
        ->capture_default_str()
        ->check(CLI::Range(0, 1024));
    command
        .add_option("--shard", options.shard,
                    "Play only shard I of N (I/N): points with index % N == I")
        ->capture_default_str();
    command.add_option("-o,--output", options.output, output);
    command.add_option("--png", options.png, png);
}

}  // namespace archet::cli
