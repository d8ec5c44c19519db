#pragma once
// An attack map drawn as a Guettler diagram: the hand's acceleration across, the bow force up,
// each attack a mark coloured by how many periods its transient lasted and shaped by how it
// began (perfect attacks stand out as the wedge between multiple slip and prolonged periods).

#include <QWidget>
#include <vector>

#include "archet/analysis/attack.hpp"

class QCustomPlot;

namespace archet::ui {

class AttackFigure : public QWidget {
    Q_OBJECT

  public:
    explicit AttackFigure(QWidget* parent = nullptr);
    void show_attacks(const AttackGrid& grid, const std::vector<AttackPoint>& points,
                      const QString& title = {});
    bool save(const QString& path, QSize size = {1000, 700});
    /// The grid point nearest the canvas position `pixel`, or −1.
    long point_at(QPoint pixel) const;
    QCustomPlot& plot() { return *plot_; }

  signals:
    void point_clicked(long index);

  private:
    QCustomPlot* plot_;
    std::vector<AttackPoint> points_;
};

/// The transient in words, for the legend and messages ("multiple slip", not "multiple_slip").
QString transient_name(Transient transient);

}  // namespace archet::ui
