#include "archet/ui/attack_figure.hpp"

#include <qcustomplot.h>

#include <QVBoxLayout>
#include <cmath>

#include "archet/ui/nearest_point.hpp"
#include "archet/ui/plot_palette.hpp"
#include "archet/ui/widget_export.hpp"

namespace archet::ui {

namespace {

// Transient lengths grouped as the diagrams in the literature shade them.
struct Band {
    double up_to;  ///< periods, inclusive
    const char* label;
    QColor colour;
};
const Band kBands[] = {{2, "up to 2 periods", {120, 200, 120}},
                       {5, "2–5 periods", {240, 200, 60}},
                       {10, "5–10 periods", {240, 140, 40}},
                       {1e9, "over 10 periods", {200, 60, 40}}};

QCPScatterStyle::ScatterShape shape_of(Transient transient) {
    switch (transient) {
        case Transient::None:
            return QCPScatterStyle::ssStar;
        case Transient::MultipleSlip:
            return QCPScatterStyle::ssCircle;
        case Transient::Prolonged:
            return QCPScatterStyle::ssSquare;
        case Transient::Sliding:
            return QCPScatterStyle::ssTriangleInverted;
        case Transient::Stuck:
            break;
    }
    return QCPScatterStyle::ssTriangle;
}

}  // namespace

QString transient_name(Transient transient) {
    switch (transient) {
        case Transient::None:
            return QObject::tr("perfect");
        case Transient::MultipleSlip:
            return QObject::tr("multiple slip");
        case Transient::Prolonged:
            return QObject::tr("prolonged periods");
        case Transient::Sliding:
            return QObject::tr("sliding");
        case Transient::Stuck:
            return QObject::tr("stuck (no slip)");
    }
    return QObject::tr("unknown");
}

AttackFigure::AttackFigure(QWidget* parent) : QWidget(parent) {
    plot_ = new QCustomPlot;
    plot_->setMinimumSize(400, 300);
    plot_->xAxis->setLabel(tr("acceleration of the hand (m/s²)"));
    plot_->yAxis->setLabel(tr("bow force (N)"));
    plot_->legend->setVisible(true);
    plot_->legend->setFont(QFont(font().family(), 8));
    plot_->plotLayout()->insertRow(0);
    plot_->plotLayout()->addElement(0, 0, new QCPTextElement(plot_, QString()));
    // The legend beside the diagram, at its top rather than spread down its height.
    auto* side = new QCPLayoutGrid;
    plot_->plotLayout()->addElement(1, 1, side);
    plot_->plotLayout()->setColumnStretchFactor(1, 0.001);
    side->addElement(0, 0, plot_->legend);
    side->addElement(1, 0, new QCPLayoutElement(plot_));
    side->setRowStretchFactor(0, 0.001);
    follow_palette(*plot_);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(plot_);
    connect(plot_, &QCustomPlot::mousePress, this, [this](QMouseEvent* e) {
        const long index = point_at(e->position().toPoint());
        if (index >= 0) emit point_clicked(index);
    });
}

void AttackFigure::show_attacks(const AttackGrid& grid, const std::vector<AttackPoint>& points,
                                const QString& title) {
    points_ = points;
    plot_->clearGraphs();
    if (auto* heading = qobject_cast<QCPTextElement*>(plot_->plotLayout()->element(0, 0)))
        heading->setText(title.isEmpty() ? tr("Attacks") : tr("Attacks: %1").arg(title));
    const auto scale = grid.log_axes ? QCPAxis::stLogarithmic : QCPAxis::stLinear;
    for (QCPAxis* axis : {plot_->xAxis, plot_->yAxis}) {
        axis->setScaleType(scale);
        if (grid.log_axes)
            axis->setTicker(QSharedPointer<QCPAxisTickerLog>(new QCPAxisTickerLog));
        else
            axis->setTicker(QSharedPointer<QCPAxisTicker>(new QCPAxisTicker));
    }
    // One scatter per kind and band of lengths, so that the legend names them.
    auto add = [&](const QString& name, QCPScatterStyle::ScatterShape shape, QColor colour,
                   auto&& chosen) {
        QVector<double> x, y;
        for (const auto& p : points)
            if (chosen(p)) x << p.acceleration, y << p.force;
        if (x.isEmpty()) return;
        QCPGraph* g = plot_->addGraph();
        g->setName(name);
        g->setLineStyle(QCPGraph::lsNone);
        g->setScatterStyle(QCPScatterStyle(shape, colour.darker(130), colour, 13));
        g->setData(x, y);
    };
    add(transient_name(Transient::None), shape_of(Transient::None), QColor(30, 140, 60),
        [](const AttackPoint& p) { return p.transient.kind == AttackKind::Perfect; });
    for (Transient transient :
         {Transient::MultipleSlip, Transient::Prolonged, Transient::Sliding, Transient::Stuck}) {
        double from = 0;
        for (const Band& band : kBands) {
            add(transient_name(transient) + ", " + tr(band.label), shape_of(transient), band.colour,
                [&](const AttackPoint& p) {
                    return p.transient.kind != AttackKind::Never &&
                           p.transient.transient == transient && p.transient.periods > from &&
                           p.transient.periods <= band.up_to;
                });
            from = band.up_to;
        }
        add(transient_name(transient) + ", " + tr("never in %1 periods").arg(grid.periods_max),
            shape_of(transient), QColor(150, 150, 150), [&](const AttackPoint& p) {
                return p.transient.kind == AttackKind::Never && p.transient.transient == transient;
            });
    }
    // A margin around the grid: a factor on log axes, a twentieth of the span on linear ones
    // (a tenth of the value for a range without span: one step, or MIN = MAX).
    auto set_range = [&](QCPAxis* axis, double lo, double hi) {
        if (grid.log_axes) return axis->setRange(lo / 1.15, hi * 1.15);
        const double pad = hi > lo ? 0.05 * (hi - lo) : 0.1 * std::abs(hi);
        axis->setRange(lo - pad, hi + pad);
    };
    set_range(plot_->xAxis, grid.acceleration_min, grid.acceleration_max);
    set_range(plot_->yAxis, grid.force_min, grid.force_max);
    apply_palette(*plot_);
    plot_->replot();
}

long AttackFigure::point_at(QPoint pixel) const {
    return nearest_point(
        *plot_, points_, pixel, [](const auto& p) { return p.acceleration; },
        [](const auto& p) { return p.force; });
}

bool AttackFigure::save(const QString& path, QSize size) {
    return save_widget_image(*this, path, size);
}

}  // namespace archet::ui
