// The graph view's zoom and pan: fitting the graph, zoom steps, the wheel, dragging the view
// along a long chain. Picking and editing are in graph_view.cpp.

#include <QKeyEvent>
#include <QScrollBar>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

#include "archet/ui/graph_view.hpp"

namespace archet::ui {

namespace {

constexpr double kZoomStep = 1.25;       // one Ctrl+= or Ctrl+-
constexpr double kMaxZoom = 8;           // view px per scene unit: a node 144 px across
constexpr double kMarginPixels = 40;     // around a fitted graph: labels keep their screen size
constexpr double kFitSlackPixels = 2;    // fitInView's own margin on each side
constexpr double kZoomOutPastFit = 0.5;  // how far below the fitted scale one may zoom out

}  // namespace

// The graph and a margin of kMarginPixels at the scale that fits both in the viewport.
QRectF GraphView::fitted_rect() const {
    const QRectF graph = graph_bounds_.isValid() && !graph_bounds_.isEmpty()
                             ? graph_bounds_
                             : QRectF(-50, -50, 100, 100);
    const QSizeF room = QSizeF(viewport()->size()) - QSizeF(2 * (kMarginPixels + kFitSlackPixels),
                                                            2 * (kMarginPixels + kFitSlackPixels));
    const double scale = std::max(std::min(room.width() / std::max(graph.width(), 1.0),
                                           room.height() / std::max(graph.height(), 1.0)),
                                  1e-3);
    const double margin = kMarginPixels / scale;
    return graph.adjusted(-margin, -margin, margin, margin);
}

// Between a little under the fitted scale and kMaxZoom (or the fitted one, if larger).
double GraphView::zoom_limited(double scale) const {
    const QRectF fitted = fitted_rect();
    const double fit_scale =
        std::min(viewport()->width() / fitted.width(), viewport()->height() / fitted.height());
    return std::clamp(scale, kZoomOutPastFit * fit_scale, std::max(kMaxZoom, fit_scale));
}

void GraphView::fit() {
    fitting_ = true;
    // The scene's extent is what a fitted view shows, so the scroll bars stay away until the
    // user zooms in (scroll bars that came and went as the view refitted resized it again).
    const QRectF fitted = fitted_rect();
    setSceneRect(fitted);
    fitInView(fitted, Qt::KeepAspectRatio);
    apply_zoom();
}

void GraphView::zoom_to(double scale) {
    zoom_about(scale, viewport()->rect().center());
}

// Zooms to `scale`, within its limits, keeping the scene point under `view_point` there.
void GraphView::zoom_about(double scale, QPoint view_point) {
    if (!(scale > 0)) return;
    fitting_ = false;
    const QPointF anchor = mapToScene(view_point);
    const double limited = zoom_limited(scale);
    setTransform(QTransform::fromScale(limited, limited));
    fit_scene_rect();
    centerOn(anchor + QPointF(viewport()->rect().center() - view_point) / limited);
    apply_zoom();
}

// The scene reaches kMarginPixels beyond the graph at the present scale: zoomed in, the
// scroll bars go no further than that into empty space (a fitted margin would be hundreds of
// scene units across a long chain's thin graph).
void GraphView::fit_scene_rect() {
    const double margin = kMarginPixels / std::max(zoom(), 1e-9);
    setSceneRect(graph_bounds_.adjusted(-margin, -margin, margin, margin));
}

void GraphView::zoom_in() {
    zoom_to(zoom() * kZoomStep);
}

void GraphView::zoom_out() {
    zoom_to(zoom() / kZoomStep);
}

// What depends on the scale: the nodes' least size on screen and which labels fit.
void GraphView::apply_zoom() {
    scale_nodes();
    thin_labels();
}

void GraphView::pan_by(QPoint pixels) {
    horizontalScrollBar()->setValue(horizontalScrollBar()->value() - pixels.x());
    verticalScrollBar()->setValue(verticalScrollBar()->value() - pixels.y());
}

void GraphView::wheelEvent(QWheelEvent* e) {
    const QPoint d = e->angleDelta();
    fitting_ = false;
    // Shift, or a sideways swipe, scrolls along the chain; otherwise the wheel zooms (with or
    // without Ctrl), about the point under the mouse.
    if ((e->modifiers() & Qt::ShiftModifier) || (d.y() == 0 && d.x() != 0)) {
        pan_by(QPoint(d.y() != 0 ? d.y() : d.x(), 0) / 2);
        return;
    }
    zoom_about(zoom() * std::pow(1.0015, d.y()), e->position().toPoint());
}

void GraphView::resizeEvent(QResizeEvent* e) {
    QGraphicsView::resizeEvent(e);
    if (fitting_) fit();
    schedule_thin_labels();  // nodes a larger view now shows (their labels were left out)
}

// Ctrl+= (or Ctrl++), Ctrl+- and Ctrl+0 when the view has the keys (the main window's View
// menu has the same shortcuts).
bool GraphView::zoom_key(QKeyEvent* e) {
    const bool ctrl = e->modifiers() & Qt::ControlModifier;
    if (e->matches(QKeySequence::ZoomIn) || (ctrl && e->key() == Qt::Key_Equal))
        zoom_in();
    else if (e->matches(QKeySequence::ZoomOut) || (ctrl && e->key() == Qt::Key_Minus))
        zoom_out();
    else if (ctrl && e->key() == Qt::Key_0)
        fit();
    else
        return false;
    return true;
}

}  // namespace archet::ui
