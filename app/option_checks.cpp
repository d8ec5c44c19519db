#include "option_checks.hpp"

#include <cmath>
#include <cstdlib>

#include "archet/input_limits.hpp"
#include "archet/number_text.hpp"
#include "archet/printable_text.hpp"

namespace archet::cli {

CLI::Validator finite_range(double lo, double hi, const std::string& unit, bool lo_open) {
    const std::string span = (lo_open ? "above " : "from ") + format_number(lo) +
                             (lo_open ? " and at most " : " to ") + format_number(hi) +
                             (unit.empty() ? "" : " " + unit);
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            char* end = nullptr;
            const double x = std::strtod(text.c_str(), &end);
            if (text.empty() || *end != '\0') return quoted_text(text) + " is not a number";
            const bool low = lo_open ? !(x > lo) : !(x >= lo);
            if (!std::isfinite(x) || low || !(x <= hi))
                return "must be " + span + " (is " + quoted_text(text) + ")";
            return {};
        },
        span);
}

CLI::Validator sample_rate_range() {
    return finite_range(limits::kMinSampleRate, limits::kMaxSampleRate, "Hz");
}

CLI::Validator duration_range(double most, const std::string& raise_with) {
    if (!std::isfinite(most))
        return CLI::Validator(
            [](std::string& text) -> std::string {
                char* end = nullptr;
                const double x = std::strtod(text.c_str(), &end);
                if (text.empty() || *end != '\0') return quoted_text(text) + " is not a number";
                return std::isfinite(x) && x > 0
                           ? ""
                           : "must be above 0 s (is " + quoted_text(text) + ")";
            },
            "above 0 s");
    CLI::Validator range = finite_range(0, most, "s", true);
    if (raise_with.empty()) return range;
    return CLI::Validator(
        [range, raise_with](std::string& text) mutable -> std::string {
            std::string problem = range(text);
            return problem.empty() ? problem : problem + "; raise " + raise_with + " to go further";
        },
        range.get_description());
}

}  // namespace archet::cli
