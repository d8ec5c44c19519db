#pragma once
// A simulation's saved state on disk (state.bin in a take): a text line naming the format and
// how many numbers follow, then the numbers as little-endian IEEE doubles, bit for bit.

#include <filesystem>
#include <vector>

namespace archet {

/// Writes `state` (from Simulation::save_state) atomically.
void write_state_file(const std::filesystem::path& path, const std::vector<double>& state);
/// Reads a state file; throws InputError naming the file and what is wrong with it.
std::vector<double> read_state_file(const std::filesystem::path& path);

}  // namespace archet
