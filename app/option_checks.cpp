#include "option_checks.hpp"

#include <cmath>
#include <cstdlib>

#include "archet/common/input_limits.hpp"
#include "archet/common/number_text.hpp"
#include "archet/common/printable_text.hpp"

namespace archet::cli {

CLI::Validator finite_range(double lo, double hi, const std::string& unit, bool lo_open) {
    // No upper bound to name when hi is infinite ("above 0 s").
    const std::string upper = std::isfinite(hi) ? format_number(hi) : std::string();
    const std::string span = (lo_open ? "above " : "from ") + format_number(lo) +
                             (upper.empty() ? "" : (lo_open ? " and at most " : " to ") + upper) +
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

CLI::Validator duration_range(double most) {
    return finite_range(0, most, "s", /*lo_open=*/true);
}

}  // namespace archet::cli
