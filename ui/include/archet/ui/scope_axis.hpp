#pragma once
// How a scope's axis follows its data without magnifying numerical noise: it spans the data
// with a margin but never less than a minimum span in the axis's unit, centred on the data,
// and labels its ticks with as many digits as tell them apart (and no more). Used by every
// autoscaled plot of the studio, so that a nearly constant trace reads as a flat line.

#include <vector>

class QCPAxis;

namespace archet::ui {

/// Fits `axis` to [lowest, highest] (in either order), at least `minimum_span` wide.
void fit_axis(QCPAxis& axis, double lowest, double highest, double minimum_span);
/// Fits `axis` to the extent of `values` (left alone when there are none).
void fit_axis(QCPAxis& axis, const std::vector<double>& values, double minimum_span);

}  // namespace archet::ui
