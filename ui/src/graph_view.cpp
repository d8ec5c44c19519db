#include "archet/ui/graph_view.hpp"

#include <QGraphicsEllipseItem>
#include <QGraphicsSceneMouseEvent>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QScrollBar>
#include <algorithm>
#include <map>

#include "archet/model/finger_contact.hpp"
#include "archet/ui/model_document.hpp"
#include "graph_node_radius.hpp"

namespace archet::ui {

namespace {

constexpr double kRadius = kNodeRadius;
// On a long chain zoomed out, nodes would shrink to specks: each keeps this radius on screen,
// and a click this near a node or link picks it.
constexpr double kMinNodePixels = 3.5;
constexpr double kPickPixels = 8;
constexpr int kIdRole = 0;  // QGraphicsItem::data key holding the element id

QColor colour_of(MatKind kind) {
    switch (kind) {
        case MatKind::Mass:
            return {60, 110, 200};
        case MatKind::Fixed:
            return {120, 120, 120};
        case MatKind::Oscillator:
            return {60, 160, 90};
        case MatKind::Gesture:
            return {230, 140, 30};
        case MatKind::ModalPoint:
            return {150, 80, 180};
    }
    return Qt::black;
}

// Links in the palette's text colour (dark on light, light on dark), slower levels orange.
QPen pen_of(LiaKind kind, bool slow, const QPalette& palette) {
    QColor ink = palette.color(QPalette::Text);
    ink.setAlpha(200);
    QPen pen(slow ? QColor(230, 140, 30) : ink, 1.6);
    if (kind == LiaKind::Damper) pen.setStyle(Qt::DashLine);
    if (kind == LiaKind::Buffer) pen.setStyle(Qt::DotLine);
    if (kind == LiaKind::SpringDamper) pen.setWidthF(2.4);
    pen.setCosmetic(true);
    return pen;
}

}  // namespace

GraphView::GraphView(ModelDocument& document, QWidget* parent)
    : QGraphicsView(parent), document_(document) {
    setScene(&scene_);
    setRenderHint(QPainter::Antialiasing);
    setDragMode(QGraphicsView::RubberBandDrag);
    setTransformationAnchor(QGraphicsView::AnchorUnderMouse);
    setMinimumHeight(160);
    // Scroll bars show once zoomed in; fit() keeps the scene to what a fitted view shows.
    setHorizontalScrollBarPolicy(Qt::ScrollBarAsNeeded);
    setVerticalScrollBarPolicy(Qt::ScrollBarAsNeeded);
    connect(&document_, &ModelDocument::changed, this, [this] { rebuild(); });
    connect(&document_, &ModelDocument::replaced, this, [this] {
        fitting_ = true;
        fit();
    });
    for (QScrollBar* bar : {horizontalScrollBar(), verticalScrollBar()})
        connect(bar, &QScrollBar::valueChanged, this, [this] { schedule_thin_labels(); });
    connect(&scene_, &QGraphicsScene::selectionChanged, this, [this] {
        thin_labels();
        emit selection_changed(selected_ids());
    });
    rebuild();
}

// The scene deselects its items as it goes: nobody should hear of it by then.
GraphView::~GraphView() {
    scene_.blockSignals(true);
    for (QScrollBar* bar : {horizontalScrollBar(), verticalScrollBar()}) bar->disconnect(this);
}

void GraphView::set_tool(Tool tool, MatKind mat, LiaKind link) {
    tool_ = tool, mat_kind_ = mat, link_kind_ = link;
    setDragMode(tool == Tool::Select ? QGraphicsView::RubberBandDrag : QGraphicsView::NoDrag);
    setCursor(tool == Tool::Select ? Qt::ArrowCursor : Qt::CrossCursor);
}

// A finger: a fingertip above the point of its string it touches, between two of its MATs.
void GraphView::add_finger(const Lia& finger, const std::map<std::string, QPointF>& at) {
    if (finger.along.size() < 2) return;
    const FingerContact contact = finger_contact(finger.finger_position, finger.along.size());
    const auto a = at.find(finger.along[contact.first]);
    const auto b = at.find(finger.along[contact.first + 1]);
    if (a == at.end() || b == at.end()) return;
    const QPointF touch = a->second + contact.weight * (b->second - a->second);
    const QPointF tip = touch + QPointF(0, -22);
    const QColor ink(60, 110, 170);
    scene_.addLine(QLineF(tip, touch), QPen(ink, 1.2 + 1.8 * finger.pressure))->setZValue(-1);
    QPolygonF fingertip({{-7, -9}, {7, -9}, {0, 5}});
    auto* item = scene_.addPolygon(fingertip, QPen(ink), QColor(170, 200, 235));
    item->setPos(tip);
    nodes_.push_back(item);
    item->setData(kIdRole, QString::fromStdString(finger.id));
    item->setFlag(QGraphicsItem::ItemIsSelectable);
    item->setFlag(QGraphicsItem::ItemIgnoresTransformations);  // a fingertip at any zoom
    item->setToolTip(tr("%1: finger at %2 of its string, pressure %3")
                         .arg(QString::fromStdString(finger.id))
                         .arg(finger.finger_position, 0, 'g', 4)
                         .arg(finger.pressure, 0, 'g', 3));
}

void GraphView::rebuild() {
    const QStringList keep = selected_ids();
    const QSignalBlocker quiet(&scene_);
    scene_.clear();
    labels_.clear(), label_sides_.clear(), label_nodes_.clear(), badges_.clear();
    badge_labels_.clear(), badge_lifts_.clear();
    nodes_.clear();
    rubber_line_ = nullptr;
    const Model& model = document_.model();
    std::map<std::string, QPointF> at;
    for (const auto& m : model.mats) at[m.id] = document_.position_of(m);
    auto slow = [&](const std::string& rate) {
        const RateLevel* r = model.find_rate(rate);
        return r && r->divider > 1;
    };
    for (const auto& l : model.lias) {
        if (l.kind == LiaKind::Finger) {
            add_finger(l, at);
            continue;
        }
        if (!at.count(l.from) || !at.count(l.to)) continue;
        if (l.kind == LiaKind::BowFriction) {  // a diamond between bow and string
            const QPointF centre = (at[l.from] + at[l.to]) / 2 + QPointF(0, -12);
            for (const auto* end : {&l.from, &l.to, &l.press, &l.surface})
                if (at.count(*end))
                    scene_
                        .addLine(QLineF(centre, at[*end]),
                                 QPen(QColor(180, 60, 40), 1.2, Qt::DashDotLine))
                        ->setZValue(-1);
            // Drawn about its own origin, so that it keeps its least size about its centre.
            QPolygonF diamond({{0, -8}, {8, 0}, {0, 8}, {-8, 0}});
            auto* item =
                scene_.addPolygon(diamond, QPen(QColor(180, 60, 40)), QColor(240, 180, 160));
            item->setPos(centre);
            nodes_.push_back(item);
            item->setData(kIdRole, QString::fromStdString(l.id));
            item->setFlag(QGraphicsItem::ItemIsSelectable);
            item->setToolTip(tr("%1: bow–string module").arg(QString::fromStdString(l.id)));
            continue;
        }
        auto* line =
            scene_.addLine(QLineF(at[l.from], at[l.to]), pen_of(l.kind, slow(l.rate), palette()));
        line->setData(kIdRole, QString::fromStdString(l.id));
        line->setFlag(QGraphicsItem::ItemIsSelectable);
        line->setZValue(-1);
        line->setToolTip(tr("%1: %2 at rate %3")
                             .arg(QString::fromStdString(l.id), to_string(l.kind),
                                  QString::fromStdString(l.rate)));
    }
    for (const auto& m : model.mats) {
        const QRectF box(-kRadius, -kRadius, 2 * kRadius, 2 * kRadius);
        QAbstractGraphicsShapeItem* node =
            m.kind == MatKind::Fixed ? static_cast<QAbstractGraphicsShapeItem*>(scene_.addRect(box))
                                     : scene_.addEllipse(box);
        node->setBrush(colour_of(m.kind));
        node->setPen(QPen(palette().color(QPalette::Base), 1.5));
        node->setPos(at[m.id]);
        nodes_.push_back(node);
        node->setData(kIdRole, QString::fromStdString(m.id));
        node->setFlags(QGraphicsItem::ItemIsSelectable | QGraphicsItem::ItemIsMovable);
        node->setToolTip(tr("%1: %2 at rate %3")
                             .arg(QString::fromStdString(m.id), to_string(m.kind),
                                  QString::fromStdString(m.rate)));
        add_labels(node, m, model);
    }
    graph_bounds_ = QRectF();
    for (QGraphicsItem* item : scene_.items())
        if (!item->parentItem()) graph_bounds_ |= item->sceneBoundingRect();
    // Room to scroll to whatever was added; a fitted view keeps the extent it fitted.
    if (!fitting_) fit_scene_rect();
    select(keep);
    apply_zoom();
}

void GraphView::scale_nodes() {
    const double least = std::max(1.0, kMinNodePixels / (kRadius * zoom()));
    for (QGraphicsItem* node : nodes_) node->setScale(least);
}

QStringList GraphView::selected_ids() const {
    QStringList ids;
    for (QGraphicsItem* item : scene_.selectedItems()) ids << item->data(kIdRole).toString();
    ids.sort();
    return ids;
}

void GraphView::select(const QStringList& ids) {
    for (QGraphicsItem* item : scene_.items())
        if (!item->data(kIdRole).toString().isEmpty())
            item->setSelected(ids.contains(item->data(kIdRole).toString()));
}

QPointF GraphView::node_position(const QString& id) const {
    for (QGraphicsItem* item : scene_.items())
        if (item->data(kIdRole).toString() == id) return item->pos();
    return {};
}

// The node or link nearest `view_point` within kPickPixels on screen, nodes first on a tie.
QGraphicsItem* GraphView::nearest_item(QPoint view_point) const {
    const QRect around(view_point - QPoint(kPickPixels, kPickPixels),
                       QSize(2 * kPickPixels + 1, 2 * kPickPixels + 1));
    QGraphicsItem* best = nullptr;
    double best_distance = kPickPixels + 1;
    const QPointF p(view_point);
    for (QGraphicsItem* item : items(around)) {
        if (!(item->flags() & QGraphicsItem::ItemIsSelectable)) continue;
        double distance = 0;
        if (const auto* line = qgraphicsitem_cast<QGraphicsLineItem*>(item)) {
            const QLineF on_screen(mapFromScene(line->line().p1()),
                                   mapFromScene(line->line().p2()));
            const QPointF d = on_screen.p2() - on_screen.p1();
            const double t = std::clamp(QPointF::dotProduct(p - on_screen.p1(), d) /
                                            std::max(QPointF::dotProduct(d, d), 1e-9),
                                        0.0, 1.0);
            distance = QLineF(p, on_screen.pointAt(t)).length() + 2;
        } else {
            distance = QLineF(p, mapFromScene(item->scenePos())).length() -
                       kRadius * item->scale() * zoom();
        }
        if (distance < best_distance) best = item, best_distance = distance;
    }
    return best;
}

// A left press in the select tool that is not plainly on one element: near one, it picks it
// (Ctrl toggles); on the background it starts panning, or with Shift the rubber band. Returns
// whether it took the press.
bool GraphView::background_press(QMouseEvent* e) {
    const QPoint at = e->position().toPoint();
    QGraphicsItem* hit = itemAt(at);
    QGraphicsItem* near = nearest_item(at);
    // Zoomed out, nodes overlap: the one whose centre is nearest wins over the topmost.
    if (hit && (hit->flags() & QGraphicsItem::ItemIsSelectable) && (!near || near == hit))
        return false;
    const bool ctrl = e->modifiers() & Qt::ControlModifier;
    if (near) {
        if (!ctrl) scene_.clearSelection();
        near->setSelected(!(ctrl && near->isSelected()));
        return true;
    }
    if (e->modifiers() & (Qt::ShiftModifier | Qt::ControlModifier)) return false;
    panning_ = true, panned_ = false, pan_last_ = at;
    return true;
}

QString GraphView::mat_at(QPointF p) const {
    for (QGraphicsItem* item : scene_.items(p)) {
        QGraphicsItem* node = item->parentItem() ? item->parentItem() : item;
        const QString id = node->data(kIdRole).toString();
        if (!id.isEmpty() && document_.model().find_mat(id.toStdString())) return id;
    }
    return {};
}

void GraphView::mousePressEvent(QMouseEvent* e) {
    const QPointF p = mapToScene(e->position().toPoint());
    if (e->button() == Qt::MiddleButton) {
        panning_ = true, panned_ = false, pan_last_ = e->position().toPoint();
        return;
    }
    if (e->button() != Qt::LeftButton) return QGraphicsView::mousePressEvent(e);
    if (tool_ == Tool::Select && background_press(e)) return;
    if (tool_ == Tool::AddMat) {
        const QString id = document_.add_mat(mat_kind_, p);
        select({id});
        return;
    }
    if (tool_ == Tool::Connect) {
        connect_from_ = mat_at(p);
        if (!connect_from_.isEmpty())
            rubber_line_ = scene_.addLine(QLineF(node_position(connect_from_), p),
                                          QPen(Qt::gray, 1, Qt::DashLine));
        return;
    }
    drag_start_ = p;
    QGraphicsView::mousePressEvent(e);
}

void GraphView::mouseMoveEvent(QMouseEvent* e) {
    if (panning_) {
        const QPoint d = e->position().toPoint() - pan_last_;
        pan_last_ = e->position().toPoint();
        if (!d.isNull()) panned_ = true, fitting_ = false;
        pan_by(d);
        return;
    }
    if (rubber_line_) {
        QLineF line = rubber_line_->line();
        line.setP2(mapToScene(e->position().toPoint()));
        rubber_line_->setLine(line);
        return;
    }
    QGraphicsView::mouseMoveEvent(e);
}

void GraphView::mouseReleaseEvent(QMouseEvent* e) {
    const QPointF p = mapToScene(e->position().toPoint());
    if (panning_) {
        panning_ = false;
        // A click on the background, not a drag: it clears the selection, as before.
        if (!panned_ && e->button() == Qt::LeftButton) scene_.clearSelection();
        return;
    }
    if (tool_ == Tool::Connect && rubber_line_) {
        const QString to = mat_at(p);
        const QString from = connect_from_;
        connect_from_.clear();
        scene_.removeItem(rubber_line_);
        delete rubber_line_;
        rubber_line_ = nullptr;
        if (!to.isEmpty() && to != from) select({document_.add_link(link_kind_, from, to)});
        return;
    }
    QGraphicsView::mouseReleaseEvent(e);
    if (drag_start_ && p != *drag_start_) {
        // Nodes dragged together: one step, by how far the first of them moved.
        QStringList moved;
        QPointF delta;
        for (const QString& id : selected_ids())
            if (const Mat* m = document_.model().find_mat(id.toStdString())) {
                const QPointF d = node_position(id) - document_.position_of(*m);
                if (d.manhattanLength() > 0.01) moved << id, delta = d;
            }
        if (!moved.isEmpty()) document_.move(moved, delta, false);
    }
    drag_start_.reset();
}

void GraphView::changeEvent(QEvent* e) {
    QGraphicsView::changeEvent(e);
    if (e->type() == QEvent::PaletteChange) rebuild();  // labels and links in the new colours
}

void GraphView::keyPressEvent(QKeyEvent* e) {
    if (e->key() == Qt::Key_Delete || e->key() == Qt::Key_Backspace) {
        const QStringList ids = selected_ids();
        if (!ids.isEmpty()) document_.remove(ids);
        return;
    }
    if (e->key() == Qt::Key_Escape) {
        set_tool(Tool::Select);
        return;
    }
    if (zoom_key(e)) return;
    QGraphicsView::keyPressEvent(e);
}

}  // namespace archet::ui
