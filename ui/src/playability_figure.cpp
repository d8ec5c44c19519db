#include "archet/ui/playability_figure.hpp"

#include <qcustomplot.h>

#include <QVBoxLayout>
#include <cmath>

#include "archet/ui/nearest_point.hpp"
#include "archet/ui/plot_palette.hpp"
#include "archet/ui/widget_export.hpp"

namespace archet::ui {

QColor regime_colour(Regime regime) {
    switch (regime) {
        case Regime::Helmholtz:
            return {40, 160, 80};
        case Regime::MultipleSlip:
            return {70, 120, 210};
        case Regime::Raucous:
            return {210, 70, 50};
        case Regime::AnomalousLow:
            return {150, 80, 180};
        case Regime::Silent:
            return {170, 170, 170};
    }
    return Qt::black;
}

QString regime_name(Regime regime) {
    switch (regime) {
        case Regime::Helmholtz:
            return QObject::tr("Helmholtz");
        case Regime::MultipleSlip:
            return QObject::tr("multiple slip");
        case Regime::Raucous:
            return QObject::tr("raucous");
        case Regime::AnomalousLow:
            return QObject::tr("anomalous low");
        case Regime::Silent:
            return QObject::tr("silent");
    }
    return QObject::tr("unknown");
}

PlayabilityFigure::PlayabilityFigure(QWidget* parent) : QWidget(parent) {
    plot_ = new QCustomPlot;
    plot_->setMinimumSize(400, 300);
    plot_->xAxis->setLabel(tr("bow position β (distance from the bridge / length)"));
    plot_->yAxis->setLabel(tr("bow force (N)"));
    plot_->yAxis->setScaleType(QCPAxis::stLogarithmic);
    plot_->yAxis->setTicker(QSharedPointer<QCPAxisTickerLog>(new QCPAxisTickerLog));
    plot_->legend->setVisible(true);
    plot_->legend->setFont(QFont(font().family(), 8));
    // The legend beside the map, not over it.
    plot_->plotLayout()->addElement(0, 1, plot_->legend);
    plot_->plotLayout()->setColumnStretchFactor(1, 0.001);
    follow_palette(*plot_);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(plot_);
    connect(plot_, &QCustomPlot::mousePress, this, [this](QMouseEvent* e) {
        const long index = point_at(e->position().toPoint());
        if (index >= 0) emit point_clicked(index);
    });
}

void PlayabilityFigure::show_map(const MapGrid& grid, const std::vector<MapPoint>& points,
                                 const SchellengLines& lines) {
    points_ = points;
    plot_->clearGraphs();
    // One scatter per regime, so that the legend names the colours.
    for (Regime r : {Regime::Helmholtz, Regime::MultipleSlip, Regime::Raucous, Regime::AnomalousLow,
                     Regime::Silent}) {
        QVector<double> x, y;
        for (const auto& p : points)
            if (p.analysis.regime == r) x << p.position, y << p.force;
        if (x.isEmpty()) continue;
        QCPGraph* g = plot_->addGraph();
        g->setName(regime_name(r));
        g->setLineStyle(QCPGraph::lsNone);
        g->setScatterStyle(
            QCPScatterStyle(QCPScatterStyle::ssSquare, regime_colour(r), regime_colour(r), 14));
        g->setData(x, y);
    }
    // Schelleng's lines, from the model's own string.
    QVector<double> beta, low, high;
    for (int i = 0; i <= 100; ++i) {
        const double b = grid.position_min * 0.9 +
                         (grid.position_max * 1.1 - grid.position_min * 0.9) * i / 100.0;
        const SchellengBounds s = lines.at(b, grid.speed);
        if (s.maximum > 0) beta << b, low << s.minimum, high << s.maximum;
    }
    if (!beta.isEmpty()) {
        for (auto [values, name] :
             {std::pair{low, tr("Schelleng minimum")}, std::pair{high, tr("Schelleng maximum")}}) {
            QCPGraph* line = plot_->addGraph();
            line->setName(name);
            line->setPen(QPen(Qt::black, 1.5, name.contains("min") ? Qt::DashLine : Qt::SolidLine));
            line->setData(beta, values);
        }
    }
    plot_->xAxis->setRange(grid.position_min - 0.01, grid.position_max + 0.01);
    plot_->yAxis->setRange(grid.force_min / 1.5, grid.force_max * 1.5);
    apply_palette(*plot_);
    plot_->replot();
}

void PlayabilityFigure::mark(std::optional<std::pair<double, double>> point) {
    for (int i = plot_->graphCount() - 1; i >= 0; --i)
        if (plot_->graph(i)->name() == tr("the gesture")) plot_->removeGraph(i);
    if (point) {
        QCPGraph* g = plot_->addGraph();
        g->setName(tr("the gesture"));
        g->setLineStyle(QCPGraph::lsNone);
        g->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCrossCircle,
                                           palette().color(QPalette::WindowText), 16));
        g->setData({point->first}, {point->second});
    }
    plot_->replot();
}

long PlayabilityFigure::point_at(QPoint pixel) const {
    return nearest_point(
        *plot_, points_, pixel, [](const auto& p) { return p.position; },
        [](const auto& p) { return p.force; });
}

bool PlayabilityFigure::save(const QString& path, QSize size) {
    return save_widget_image(*this, path, size);
}

}  // namespace archet::ui
