#include "archet/ui/scope_axis.hpp"

#include <qcustomplot.h>

#include <algorithm>
#include <cmath>

namespace archet::ui {

namespace {

constexpr double kMargin = 0.1;  // of the data's extent, on each side
constexpr int kFewestDigits = 3;
constexpr int kMostDigits = 15;  // beyond, a double's round-off would show in the labels

// Significant digits that tell apart ticks a tenth of the span apart (the ticker places about
// five), at the range's largest magnitude.
int digits_for(double lower, double upper) {
    const double magnitude = std::max(std::abs(lower), std::abs(upper));
    const double finest_step = (upper - lower) / 10;
    const int digits =
        static_cast<int>(std::floor(std::log10(magnitude)) - std::floor(std::log10(finest_step))) +
        2;
    return std::clamp(digits, kFewestDigits, kMostDigits);
}

}  // namespace

void fit_axis(QCPAxis& axis, double lowest, double highest, double minimum_span) {
    if (!std::isfinite(lowest) || !std::isfinite(highest)) return;
    if (lowest > highest) std::swap(lowest, highest);
    const double centre = 0.5 * (lowest + highest);
    double half = std::max(0.5 * (highest - lowest) * (1 + 2 * kMargin), 0.5 * minimum_span);
    if (!(half > 0)) half = 0.5;  // no data extent and no minimum: any span will do
    axis.setRange(centre - half, centre + half);
    axis.setNumberPrecision(digits_for(centre - half, centre + half));
}

void fit_axis(QCPAxis& axis, const std::vector<double>& values, double minimum_span) {
    if (values.empty()) return;
    const auto [lowest, highest] = std::minmax_element(values.begin(), values.end());
    fit_axis(axis, *lowest, *highest, minimum_span);
}

}  // namespace archet::ui
