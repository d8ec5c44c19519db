#pragma once
// Checks of numeric command-line values, applied as the line is parsed so that a bad value
// is refused (status 2) before any work starts: CLI11's own ranges let NaN through.

#include <CLI/CLI.hpp>
#include <string>

namespace archet::cli {

/// A finite number in [lo, hi] (or (lo, hi] when `lo_open`), with its unit in the message.
CLI::Validator finite_range(double lo, double hi, const std::string& unit, bool lo_open = false);

/// A master clock in the range a model accepts (1000 to 1000000 Hz).
CLI::Validator sample_rate_range();

/// Seconds above 0 and at most `most` (infinity: no bound here; the flag that raises the
/// bound, if any, is named in the message).
CLI::Validator duration_range(double most, const std::string& raise_with = "");

}  // namespace archet::cli
