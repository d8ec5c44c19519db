#include "archet/ui/plot_palette.hpp"

#include <qcustomplot.h>

#include <QEvent>
#include <QPalette>

namespace archet::ui {

namespace {

constexpr const char* kLightColour = "archet_light_colour";  // a pen's colour as it was set

// The colour a series was given for a light background, and what it becomes on a dark one:
// brighter, and black (or nearly) becomes the palette's text colour.
QColor for_background(QObject& item, const QColor& current, const QPalette& palette) {
    if (!item.property(kLightColour).isValid()) item.setProperty(kLightColour, current);
    const QColor light = item.property(kLightColour).value<QColor>();
    if (!is_dark(palette)) return light;
    return light.lightness() < 80 ? palette.color(QPalette::WindowText) : light.lighter(170);
}

}  // namespace

void apply_palette(QCustomPlot& plot) {
    const QPalette& palette = plot.palette();
    const QColor text = palette.color(QPalette::WindowText);
    const QColor grid = palette.color(QPalette::Mid);
    plot.setBackground(palette.brush(QPalette::Base));
    for (QCPAxis* axis : plot.axisRect() ? plot.axisRect()->axes() : QList<QCPAxis*>{}) {
        axis->setBasePen(QPen(text, 1));
        axis->setTickPen(QPen(text, 1));
        axis->setSubTickPen(QPen(text, 1));
        axis->setTickLabelColor(text);
        axis->setLabelColor(text);
        axis->grid()->setPen(QPen(grid, 1, Qt::DotLine));
        axis->grid()->setSubGridPen(Qt::NoPen);
        axis->grid()->setZeroLinePen(QPen(grid, 1));
    }
    if (plot.legend) {
        plot.legend->setBrush(palette.brush(QPalette::Base));
        plot.legend->setBorderPen(QPen(grid));
        plot.legend->setTextColor(text);
    }
    for (int i = 0; i < plot.plotLayout()->elementCount(); ++i)
        if (auto* title = qobject_cast<QCPTextElement*>(plot.plotLayout()->elementAt(i)))
            title->setTextColor(text);
    for (int i = 0; i < plot.plottableCount(); ++i) {
        QCPAbstractPlottable& p = *plot.plottable(i);
        QPen pen = p.pen();
        pen.setColor(for_background(p, pen.color(), palette));
        p.setPen(pen);
    }
    for (int i = 0; i < plot.itemCount(); ++i)
        if (auto* label = qobject_cast<QCPItemText*>(plot.item(i)))
            label->setColor(for_background(*label, label->color(), palette));
    plot.replot(QCustomPlot::rpQueuedReplot);
}

namespace {

class PaletteFollower : public QObject {
  public:
    explicit PaletteFollower(QCustomPlot& plot) : QObject(&plot), plot_(plot) {
        plot.installEventFilter(this);
    }
    bool eventFilter(QObject*, QEvent* e) override {
        if (e->type() == QEvent::PaletteChange) apply_palette(plot_);
        return false;
    }

  private:
    QCustomPlot& plot_;
};

}  // namespace

bool is_dark(const QPalette& palette) {
    return palette.color(QPalette::Base).lightness() < palette.color(QPalette::Text).lightness();
}

void follow_palette(QCustomPlot& plot) {
    apply_palette(plot);
    new PaletteFollower(plot);
}

}  // namespace archet::ui
