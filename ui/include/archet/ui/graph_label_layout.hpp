#pragma once
// Where the graph's id labels stand: under their nodes, or beside or above them where under
// would cover another node (a body's modes hang in a column beside and under its bridge).
// Everything is worked out on screen from the nodes' transforms: a label's item moves only when its
// side changes, so a zoom step leaves the scene's index alone (moving items to try places rebuilt
// it, for every label).

#include <QGraphicsItem>
#include <QGraphicsSimpleTextItem>
#include <QRectF>
#include <QTransform>
#include <vector>

namespace archet::ui {

enum class LabelSide { Below, Left, Right, Above };

/// The sides a label tries, in order, where under its node it would cover another node.
inline constexpr LabelSide kLabelSidesBeside[] = {LabelSide::Left, LabelSide::Right,
                                                  LabelSide::Above};

/// Puts an id label (a child of its node, drawn at screen size) on `side` of its node, `gap`
/// scene units from its centre and `lift` pixels further out (past another label there).
void place_label(QGraphicsSimpleTextItem& label, LabelSide side, double gap, double lift = 0);

/// Where `label` would stand on screen on `side`, its node drawn by `node_to_screen`.
QRectF label_box(const QGraphicsSimpleTextItem& label, const QTransform& node_to_screen,
                 LabelSide side, double gap, double lift = 0);

/// The boxes on screen of the nodes in and near the viewport, kept in a grid of square cells
/// over it, to find in a few lookups which nodes a label's box would cover.
class NodeBoxes {
  public:
    /// `area`: the viewport and a margin around it, on screen.
    NodeBoxes(const QRectF& area, double cell);
    void add(const QGraphicsItem* node, const QRectF& box);
    /// Whether `box` meets the box of a node other than `own`.
    bool covers_another(const QRectF& box, const QGraphicsItem* own) const;

  private:
    struct Entry {
        const QGraphicsItem* node;
        QRectF box;
    };
    /// The cells `box` meets, clamped to the grid: first and last column and row.
    bool cells_of(const QRectF& box, int& c0, int& c1, int& r0, int& r1) const;

    QRectF area_;
    double cell_;
    int columns_, rows_;
    std::vector<Entry> entries_;
    std::vector<std::vector<int>> cells_;  ///< per cell, indices into entries_
};

}  // namespace archet::ui
