#pragma once
// The grid point of a diagram nearest a click, for the figures that play a clicked point.

#include <qcustomplot.h>

#include <cmath>

namespace archet::ui {

/// The index of the point of `points` drawn nearest `pixel` on `plot` (at `x(p)`, `y(p)` in
/// the axes' coordinates), or −1 when none is within 15 pixels.
template <class Points, class X, class Y>
long nearest_point(const QCustomPlot& plot, const Points& points, QPoint pixel, X x, Y y) {
    long best = -1;
    double nearest = 15;  // px
    for (const auto& p : points) {
        const double dx = plot.xAxis->coordToPixel(x(p)) - pixel.x();
        const double dy = plot.yAxis->coordToPixel(y(p)) - pixel.y();
        const double d = std::hypot(dx, dy);
        if (d < nearest) nearest = d, best = static_cast<long>(p.index);
    }
    return best;
}

}  // namespace archet::ui
