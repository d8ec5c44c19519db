#include "archet/ui/graph_label_layout.hpp"

#include <algorithm>
#include <cmath>

namespace archet::ui {

namespace {

constexpr double kBeside = 2;  // px between a node and a label beside it

// Where the label's origin goes in its node's coordinates, and its box from there in pixels.
QPointF anchor(LabelSide side, double gap) {
    switch (side) {
        case LabelSide::Below:
            return {0, gap};
        case LabelSide::Above:
            return {0, -gap};
        case LabelSide::Left:
            return {-gap, 0};
        case LabelSide::Right:
            return {gap, 0};
    }
    return {};
}

QPointF offset(LabelSide side, const QSizeF& size, double lift) {
    switch (side) {
        case LabelSide::Below:
            return {-size.width() / 2, lift};
        case LabelSide::Above:
            return {-size.width() / 2, -size.height() - lift};
        case LabelSide::Left:
            return {-size.width() - kBeside - lift, -size.height() / 2};
        case LabelSide::Right:
            return {kBeside + lift, -size.height() / 2};
    }
    return {};
}

}  // namespace

void place_label(QGraphicsSimpleTextItem& label, LabelSide side, double gap, double lift) {
    const QPointF shift = offset(side, label.boundingRect().size(), lift);
    label.setPos(anchor(side, gap));
    label.setTransform(QTransform::fromTranslate(shift.x(), shift.y()));
}

QRectF label_box(const QGraphicsSimpleTextItem& label, const QTransform& node_to_screen,
                 LabelSide side, double gap, double lift) {
    const QSizeF size = label.boundingRect().size();
    return {node_to_screen.map(anchor(side, gap)) + offset(side, size, lift), size};
}

NodeBoxes::NodeBoxes(const QRectF& area, double cell)
    : area_(area),
      cell_(cell),
      columns_(std::max(1, static_cast<int>(std::ceil(area.width() / cell)))),
      rows_(std::max(1, static_cast<int>(std::ceil(area.height() / cell)))),
      cells_(static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_)) {}

bool NodeBoxes::cells_of(const QRectF& box, int& c0, int& c1, int& r0, int& r1) const {
    if (!box.intersects(area_)) return false;
    auto column = [&](double x) {
        return std::clamp(static_cast<int>((x - area_.left()) / cell_), 0, columns_ - 1);
    };
    auto row = [&](double y) {
        return std::clamp(static_cast<int>((y - area_.top()) / cell_), 0, rows_ - 1);
    };
    c0 = column(box.left()), c1 = column(box.right());
    r0 = row(box.top()), r1 = row(box.bottom());
    return true;
}

void NodeBoxes::add(const QGraphicsItem* node, const QRectF& box) {
    int c0, c1, r0, r1;
    if (!cells_of(box, c0, c1, r0, r1)) return;
    const int entry = static_cast<int>(entries_.size());
    entries_.push_back({node, box});
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c) cells_[r * columns_ + c].push_back(entry);
}

bool NodeBoxes::covers_another(const QRectF& box, const QGraphicsItem* own) const {
    int c0, c1, r0, r1;
    if (!cells_of(box, c0, c1, r0, r1)) return false;
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c)
            for (int entry : cells_[r * columns_ + c]) {
                const Entry& e = entries_[entry];
                if (e.node != own && e.box.intersects(box)) return true;
            }
    return false;
}

}  // namespace archet::ui
