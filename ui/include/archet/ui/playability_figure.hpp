#pragma once
// A playability map drawn as Schelleng's diagram: bow position β across, bow force up (log),
// each run a square coloured by its regime, with Schelleng's two lines from the string's own
// parameters and, optionally, where the current gesture bows.

#include <QWidget>
#include <optional>
#include <vector>

#include "archet/analysis/playability.hpp"

class QCustomPlot;

namespace archet::ui {

class PlayabilityFigure : public QWidget {
    Q_OBJECT

  public:
    explicit PlayabilityFigure(QWidget* parent = nullptr);
    /// The points, with Schelleng's lines of the model's string (PlayedMap::lines).
    void show_map(const MapGrid& grid, const std::vector<MapPoint>& points,
                  const SchellengLines& lines);
    /// Marks (β, force) on the map, e.g. the gesture being played.
    void mark(std::optional<std::pair<double, double>> point);
    bool save(const QString& path, QSize size = {1000, 700});
    /// The grid point nearest the canvas position `pixel`, or −1.
    long point_at(QPoint pixel) const;
    QCustomPlot& plot() { return *plot_; }

  signals:
    void point_clicked(long index);

  private:
    QCustomPlot* plot_;
    std::vector<MapPoint> points_;
};

QColor regime_colour(Regime regime);
/// The regime in words, for the legend and messages ("multiple slip", not "multiple_slip").
QString regime_name(Regime regime);

}  // namespace archet::ui
