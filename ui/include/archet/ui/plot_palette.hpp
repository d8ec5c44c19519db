#pragma once
// Plots that follow the window's palette: background, axes, ticks, labels, grid, legend and
// titles in the palette's colours, and the data drawn brighter on a dark background, so that
// a plot stays legible in a light and a dark desktop alike. Restyled whenever the palette
// changes.

class QCustomPlot;
class QPalette;

namespace archet::ui {

/// Styles `plot` from its palette now and on every later palette change. Call it once its
/// series exist; a plot that adds series later calls apply_palette() after adding them.
void follow_palette(QCustomPlot& plot);
void apply_palette(QCustomPlot& plot);

/// Whether a palette is dark (its base darker than its text).
bool is_dark(const QPalette& palette);

}  // namespace archet::ui
