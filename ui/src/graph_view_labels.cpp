// The graph view's id labels and rate badges: added with their nodes, and placed on screen
// where they fit (thin_labels()). Drawing and editing the graph are in graph_view.cpp.

#include <QGraphicsSimpleTextItem>
#include <algorithm>
#include <optional>

#include "archet/ui/graph_label_layout.hpp"
#include "archet/ui/graph_view.hpp"
#include "graph_node_radius.hpp"

namespace archet::ui {

namespace {

constexpr double kRadius = kNodeRadius;
// Labels keep their size on screen whatever the zoom; where they would overlap, some are
// hidden (the tooltip and the selection still show every id).
constexpr int kLabelPixels = 11;
constexpr int kBadgePixels = 9;
constexpr double kLabelGap = 4;              // px between two labels shown side by side
constexpr double kLabelBelow = kRadius + 1;  // scene units from a node's centre to its id
constexpr double kNodeRim = 2;               // px of a node's box on screen that a label may touch
constexpr double kNodeCell = 32;             // px, the side of a cell of the nodes' grid on screen
// px around the viewport within which a node's label is placed: a label stands up to a node's
// radius at the largest zoom (80 px) and its own width from the node's centre.
constexpr double kNear = 200;

// A label drawn at screen size on `side` of its node, `gap` scene units from its centre.
QGraphicsSimpleTextItem* add_label(QGraphicsItem* node, const QString& text, int pixels,
                                   const QColor& colour, LabelSide side, double gap) {
    auto* label = new QGraphicsSimpleTextItem(text, node);
    QFont font = label->font();
    font.setPixelSize(pixels);
    label->setFont(font);
    label->setBrush(colour);
    label->setFlag(QGraphicsItem::ItemIgnoresTransformations);
    place_label(*label, side, gap);
    return label;
}

// The name of a node's rate level, shown above it, where the level is not at the master clock.
QString rate_badge(const Model& model, const std::string& rate) {
    const RateLevel* r = model.find_rate(rate);
    return r && r->divider != 1 ? QString::fromStdString(rate) : QString();
}

}  // namespace

// The node's id, under it until thin_labels() places it, and its rate level's name above it
// where that is not the audio rate.
void GraphView::add_labels(QGraphicsItem* node, const Mat& m, const Model& model) {
    labels_.push_back(add_label(node, QString::fromStdString(m.id), kLabelPixels,
                                palette().color(QPalette::Text), LabelSide::Below, kLabelBelow));
    label_sides_.push_back(LabelSide::Below);
    label_nodes_.push_back(nodes_.size() - 1);
    const QString badge = rate_badge(model, m.rate);
    if (badge.isEmpty()) return;
    badges_.push_back(
        add_label(node, badge, kBadgePixels, QColor(230, 140, 30), LabelSide::Above, kRadius));
    badge_labels_.push_back(labels_.size() - 1);
    badge_lifts_.push_back(0);
}

// Shows the labels that fit on screen without overlapping: the selected nodes' ids first, then
// the others in model order, then the rate badges. An id stands under its node and is hidden
// where it would overlap a label shown before it; where under it would cover another node, it
// stands beside or above it (graph_label_layout.hpp). Only the nodes on screen or near it are
// looked at: a scroll places the labels again (schedule_thin_labels()).
void GraphView::thin_labels() {
    thin_labels_pending_ = false;
    const QTransform view = viewportTransform();
    const QRectF near = QRectF(viewport()->rect()).adjusted(-kNear, -kNear, kNear, kNear);
    const QRectF near_in_scene = mapToScene(near.toAlignedRect()).boundingRect();
    NodeBoxes nodes(near, kNodeCell);
    std::vector<QTransform> to_screen(nodes_.size());
    std::vector<char> nearby(nodes_.size(), 0);
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        if (!near_in_scene.contains(nodes_[i]->scenePos())) continue;
        nearby[i] = 1;
        to_screen[i] = nodes_[i]->deviceTransform(view);
        nodes.add(nodes_[i], to_screen[i]
                                 .mapRect(nodes_[i]->boundingRect())
                                 .adjusted(kNodeRim, kNodeRim, -kNodeRim, -kNodeRim));
    }
    std::vector<std::size_t> order;  // indices into labels_
    for (std::size_t i = 0; i < labels_.size(); ++i)
        if (labels_[i]->parentItem()->isSelected()) order.push_back(i);
    const std::size_t always_shown = order.size();
    for (std::size_t i = 0; i < labels_.size(); ++i)
        if (!labels_[i]->parentItem()->isSelected()) order.push_back(i);
    std::vector<QRectF> shown;
    auto free = [&](const QRectF& box) {
        return std::none_of(shown.begin(), shown.end(),
                            [&](const QRectF& other) { return other.intersects(box); });
    };
    auto spaced = [](const QRectF& box) { return box.adjusted(-kLabelGap, 0, kLabelGap, 0); };
    for (std::size_t k = 0; k < order.size(); ++k) {
        QGraphicsSimpleTextItem& label = *labels_[order[k]];
        const std::size_t node = label_nodes_[order[k]];
        if (!nearby[node]) {
            label.setVisible(false);
            continue;
        }
        auto box_on = [&](LabelSide side) {
            return label_box(label, to_screen[node], side, kLabelBelow);
        };
        std::optional<LabelSide> side;
        if (free(spaced(box_on(LabelSide::Below)))) {
            if (!nodes.covers_another(box_on(LabelSide::Below), label.parentItem()))
                side = LabelSide::Below;
            for (std::size_t i = 0; !side && i < std::size(kLabelSidesBeside); ++i) {
                const QRectF box = box_on(kLabelSidesBeside[i]);
                if (free(spaced(box)) && !nodes.covers_another(box, label.parentItem()))
                    side = kLabelSidesBeside[i];
            }
        }
        LabelSide& placed = label_sides_[order[k]];
        const LabelSide wanted = side.value_or(LabelSide::Below);
        if (wanted != placed) place_label(label, wanted, kLabelBelow), placed = wanted;
        label.setVisible(side.has_value() || k < always_shown);
        if (label.isVisible()) shown.push_back(spaced(box_on(wanted)));
    }
    // A badge stands above its node, and over the node's id where the id stands there.
    for (std::size_t b = 0; b < badges_.size(); ++b) {
        QGraphicsSimpleTextItem& badge = *badges_[b];
        const std::size_t id = badge_labels_[b], node = label_nodes_[id];
        if (!nearby[node]) {
            badge.setVisible(false);
            continue;
        }
        const bool id_above = labels_[id]->isVisible() && label_sides_[id] == LabelSide::Above;
        const double gap = id_above ? kLabelBelow : kRadius;
        // One pixel more than the id's height: the two boxes, rounded apart, never touch.
        const double lift = id_above ? labels_[id]->boundingRect().height() + 1 : 0.0;
        if (lift != badge_lifts_[b])
            place_label(badge, LabelSide::Above, gap, lift), badge_lifts_[b] = lift;
        const QRectF box = spaced(label_box(badge, to_screen[node], LabelSide::Above, gap, lift));
        badge.setVisible(free(box));
        if (badge.isVisible()) shown.push_back(box);
    }
}

// One pass after the scroll bars have settled (a zoom about a point moves both), unless one
// has run since (thin_labels() clears the flag).
void GraphView::schedule_thin_labels() {
    if (thin_labels_pending_) return;
    thin_labels_pending_ = true;
    QMetaObject::invokeMethod(
        this,
        [this] {
            if (thin_labels_pending_) thin_labels();
        },
        Qt::QueuedConnection);
}

QRectF GraphView::label_on_screen(const QGraphicsSimpleTextItem& label) const {
    return label.deviceTransform(viewportTransform()).mapRect(label.boundingRect());
}

std::vector<const QGraphicsSimpleTextItem*> GraphView::labels() const {
    return {labels_.begin(), labels_.end()};
}

std::vector<const QGraphicsSimpleTextItem*> GraphView::badges() const {
    return {badges_.begin(), badges_.end()};
}

}  // namespace archet::ui
