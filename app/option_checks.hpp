#pragma once
// Checks of numeric command-line values, applied as the line is parsed so that a bad value
// is refused (status 2) before any work starts: CLI11's own ranges let NaN through.

#include <CLI/CLI.hpp>
#include <string>

namespace archet::cli {

/// A finite number in [lo, hi] (or (lo, hi] when `lo_open`; hi may be infinite), with its
/// unit in the message.
CLI::Validator finite_range(double lo, double hi, const std::string& unit, bool lo_open = false);

/// A master clock in the range a model accepts (1000 to 1000000 Hz).
CLI::Validator sample_rate_range();

/// Seconds above 0 and at most `most` (infinity: no bound here, the command checks its own).
CLI::Validator duration_range(double most);

}  // namespace archet::cli
