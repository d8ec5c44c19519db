#include "archet/ui/compare_figure.hpp"

#include <qcustomplot.h>

#include <QGridLayout>
#include <QLabel>
#include <algorithm>

#include "archet/ui/plot_palette.hpp"
#include "archet/ui/widget_export.hpp"

namespace archet::ui {

namespace {
constexpr double kShownSeconds = 0.03;  // 30 ms: a few periods of steady bowing

QCustomPlot* plot(const QString& x, const QString& y) {
    auto* p = new QCustomPlot;
    p->setMinimumSize(260, 200);
    p->xAxis->setLabel(x);
    p->yAxis->setLabel(y);
    return p;
}
}  // namespace

CompareFigure::CompareFigure(QWidget* parent) : QWidget(parent) {
    grid_ = new QGridLayout(this);
}

void CompareFigure::show_runs(const std::vector<ComparisonRun>& runs) {
    while (QLayoutItem* item = grid_->takeAt(0)) {
        delete item->widget();
        delete item;
    }
    columns_ = static_cast<int>(runs.size());
    double force_lo = 0, force_hi = 0;  // one force scale for all: comparable at a glance
    for (const auto& r : runs)
        for (std::size_t i = r.steady_end / 2; i < std::min(r.steady_end, r.bow_force.size()); ++i)
            force_lo = std::min(force_lo, r.bow_force[i]),
            force_hi = std::max(force_hi, r.bow_force[i]);
    for (int c = 0; c < columns_; ++c) {
        const ComparisonRun& r = runs[static_cast<std::size_t>(c)];
        // The last periods of steady bowing.
        const std::size_t end = std::min(r.steady_end, r.bow_force.size());
        const auto shown =
            std::min<std::size_t>(end, static_cast<std::size_t>(kShownSeconds * r.sample_rate));
        const std::size_t first = end - shown;
        QVector<double> t, force, x;
        for (std::size_t i = first; i < end; ++i) {
            t << 1e3 * static_cast<double>(i - first) / r.sample_rate;
            force << r.bow_force[i];
            x << 1e3 * r.displacement[i];
        }
        auto* title =
            new QLabel(tr("<b>%1</b><br>f1 %2 Hz · the string dissipates %3 µJ per period")
                           .arg(QString::fromStdString(r.label))
                           .arg(r.fundamental, 0, 'f', 2)
                           .arg(1e6 * r.dissipated_per_period, 0, 'f', 3));
        title->setAlignment(Qt::AlignCenter);
        auto* trace = plot(tr("ms"), tr("bow force (N)"));
        trace->addGraph()->setData(t, force, true);
        trace->graph(0)->setPen(QPen(QColor(30, 90, 180), 1.3));
        trace->xAxis->setRange(0, 1e3 * kShownSeconds);
        trace->yAxis->setRange(force_lo * 1.1 - 0.01, force_hi * 1.1 + 0.01);  // shared: comparable
        auto* xy = plot(tr("displacement (mm)"), tr("bow force (N)"));
        auto* curve = new QCPCurve(xy->xAxis, xy->yAxis);
        curve->setData(x, force);
        curve->setPen(QPen(QColor(120, 40, 160), 1.2));
        xy->rescaleAxes();
        xy->yAxis->setRange(force_lo * 1.1 - 0.01, force_hi * 1.1 + 0.01);
        follow_palette(*trace);
        follow_palette(*xy);
        grid_->addWidget(title, 0, c);
        grid_->addWidget(trace, 1, c);
        grid_->addWidget(xy, 2, c);
    }
    grid_->setRowStretch(0, 0);
    grid_->setRowStretch(1, 1);
    grid_->setRowStretch(2, 1);
}

bool CompareFigure::save(const QString& path, QSize size) {
    return save_widget_image(*this, path, size);
}

}  // namespace archet::ui
