#pragma once
// Numbers and counts as they read in messages: "must be above 0", "(is 0.3)", "1 element",
// "3 elements"; never std::to_string's "0.000000".

#include <cstddef>
#include <string>
#include <string_view>

namespace archet {

/// The shortest text that reads back as `x` ("0", "0.3", "1e-05", "48000"), so that what the
/// user typed comes back as typed; a computed number that would take more than 9 digits is
/// rounded to 6 significant ones, like printf's %g ("0.333333").
std::string format_number(double x);

/// "1 element", "3 elements": `count` with the noun that agrees with it.
std::string count_of(std::size_t count, std::string_view singular, std::string_view plural);

}  // namespace archet
