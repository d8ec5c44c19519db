#include "archet/ui/graph_view.hpp"

#include <QGraphicsEllipseItem>
#include <QGraphicsSceneMouseEvent>
#include <QGraphicsSimpleTextItem>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QScrollBar>
#include <QWheelEvent>
#include <cmath>
#include <map>

#include "archet/ui/model_document.hpp"

namespace archet::ui {

namespace {

constexpr double kRadius = 9;
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

QPen pen_of(LiaKind kind, bool slow) {
    QPen pen(slow ? QColor(230, 140, 30) : QColor(50, 50, 50), 1.6);
    if (kind == LiaKind::Damper) pen.setStyle(Qt::DashLine);
    if (kind == LiaKind::Buffer) pen.setStyle(Qt::DotLine);
    if (kind == LiaKind::SpringDamper) pen.setWidthF(2.4);
    pen.setCosmetic(true);
    return pen;
}

// A short name for a rate level under each node: its divider ("1", "16").
QString rate_badge(const Model& model, const std::string& rate) {
    const RateLevel* r = model.find_rate(rate);
    return r && r->divider != 1 ? QString::fromStdString(rate) : QString();
}

}  // namespace

GraphView::GraphView(ModelDocument& document, QWidget* parent)
    : QGraphicsView(parent), document_(document) {
    setScene(&scene_);
    setRenderHint(QPainter::Antialiasing);
    setDragMode(QGraphicsView::RubberBandDrag);
    setTransformationAnchor(QGraphicsView::AnchorUnderMouse);
    setMinimumHeight(160);
    connect(&document_, &ModelDocument::changed, this, [this] { rebuild(); });
    connect(&scene_, &QGraphicsScene::selectionChanged, this,
            [this] { emit selection_changed(selected_ids()); });
    rebuild();
}

// The scene deselects its items as it goes: nobody should hear of it by then.
GraphView::~GraphView() {
    scene_.blockSignals(true);
}

void GraphView::set_tool(Tool tool, MatKind mat, LiaKind link) {
    tool_ = tool, mat_kind_ = mat, link_kind_ = link;
    setDragMode(tool == Tool::Select ? QGraphicsView::RubberBandDrag : QGraphicsView::NoDrag);
    setCursor(tool == Tool::Select ? Qt::ArrowCursor : Qt::CrossCursor);
}

void GraphView::rebuild() {
    const QStringList keep = selected_ids();
    const QSignalBlocker quiet(&scene_);
    scene_.clear();
    rubber_line_ = nullptr;
    const Model& model = document_.model();
    std::map<std::string, QPointF> at;
    for (const auto& m : model.mats) at[m.id] = document_.position_of(m);
    auto slow = [&](const std::string& rate) {
        const RateLevel* r = model.find_rate(rate);
        return r && r->divider > 1;
    };
    for (const auto& l : model.lias) {
        if (!at.count(l.from) || !at.count(l.to)) continue;
        if (l.kind == LiaKind::BowFriction) {  // a diamond between bow and string
            const QPointF centre = (at[l.from] + at[l.to]) / 2 + QPointF(0, -12);
            for (const auto* end : {&l.from, &l.to, &l.press, &l.surface})
                if (at.count(*end))
                    scene_
                        .addLine(QLineF(centre, at[*end]),
                                 QPen(QColor(180, 60, 40), 1.2, Qt::DashDotLine))
                        ->setZValue(-1);
            QPolygonF diamond({centre + QPointF(0, -8), centre + QPointF(8, 0),
                               centre + QPointF(0, 8), centre + QPointF(-8, 0)});
            auto* item =
                scene_.addPolygon(diamond, QPen(QColor(180, 60, 40)), QColor(240, 180, 160));
            item->setData(kIdRole, QString::fromStdString(l.id));
            item->setFlag(QGraphicsItem::ItemIsSelectable);
            item->setToolTip(tr("%1: bow–string module").arg(QString::fromStdString(l.id)));
            continue;
        }
        auto* line = scene_.addLine(QLineF(at[l.from], at[l.to]), pen_of(l.kind, slow(l.rate)));
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
        node->setPen(QPen(Qt::white, 1.5));
        node->setPos(at[m.id]);
        node->setData(kIdRole, QString::fromStdString(m.id));
        node->setFlags(QGraphicsItem::ItemIsSelectable | QGraphicsItem::ItemIsMovable);
        node->setToolTip(tr("%1: %2 at rate %3")
                             .arg(QString::fromStdString(m.id), to_string(m.kind),
                                  QString::fromStdString(m.rate)));
        auto* label = new QGraphicsSimpleTextItem(QString::fromStdString(m.id), node);
        label->setFont(QFont(font().family(), 7));
        label->setPos(-label->boundingRect().width() / 2, kRadius + 1);
        const QString badge = rate_badge(model, m.rate);
        if (!badge.isEmpty()) {
            auto* rate = new QGraphicsSimpleTextItem(badge, node);
            rate->setFont(QFont(font().family(), 6));
            rate->setBrush(QColor(230, 140, 30));
            rate->setPos(-rate->boundingRect().width() / 2, -kRadius - 11);
        }
    }
    select(keep);
}

void GraphView::fit() {
    fitInView(scene_.itemsBoundingRect().adjusted(-30, -30, 30, 30), Qt::KeepAspectRatio);
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
        panning_ = true, pan_last_ = e->position().toPoint();
        return;
    }
    if (e->button() != Qt::LeftButton) return QGraphicsView::mousePressEvent(e);
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
        horizontalScrollBar()->setValue(horizontalScrollBar()->value() - d.x());
        verticalScrollBar()->setValue(verticalScrollBar()->value() - d.y());
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

void GraphView::wheelEvent(QWheelEvent* e) {
    const double factor = std::pow(1.0015, e->angleDelta().y());
    scale(factor, factor);
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
    QGraphicsView::keyPressEvent(e);
}

}  // namespace archet::ui
