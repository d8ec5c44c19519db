#pragma once
// The mass-interaction graph on a canvas (QGraphicsView): MATs as nodes, LIAs as edges, the
// bow module as a diamond joining its four MATs; each shows its rate level. A tool chooses
// what a click does: select (rubber band, drag to move), place a MAT, or drag from one MAT
// to another to connect them. The wheel (or Ctrl+wheel, Ctrl+= / Ctrl+-) zooms, Ctrl+0 fits;
// dragging the background (or with the middle button) pans, Shift+drag draws the rubber
// band. Long chains stay editable: nodes keep a least size on screen and a click picks the
// nearest one. Every edit goes through the ModelDocument, so it can be undone.

#include <QGraphicsView>
#include <QStringList>
#include <map>
#include <optional>
#include <vector>

#include "archet/model/model.hpp"
#include "archet/ui/graph_label_layout.hpp"

class QGraphicsSimpleTextItem;

namespace archet::ui {

class ModelDocument;

class GraphView : public QGraphicsView {
    Q_OBJECT

  public:
    enum class Tool { Select, AddMat, Connect };

    explicit GraphView(ModelDocument& document, QWidget* parent = nullptr);
    ~GraphView() override;

    void set_tool(Tool tool, MatKind mat = MatKind::Mass, LiaKind link = LiaKind::Spring);
    Tool tool() const { return tool_; }
    QStringList selected_ids() const;
    void select(const QStringList& ids);
    /// Fits the whole graph in view, and follows the view's size again until the user zooms
    /// or pans. It does so by itself on a new model.
    void fit();
    /// One zoom step in or out about the centre (Ctrl+= and Ctrl+-).
    void zoom_in();
    void zoom_out();
    /// Zooms to `scale` (view pixels per scene unit) about the centre, as if the user had: the
    /// view no longer refits itself when resized.
    void zoom_to(double scale);
    double zoom() const { return transform().m11(); }
    /// Whether the view still fits itself to its size (the user has not zoomed or panned).
    bool fitting() const { return fitting_; }

    /// For tests and scripting: the canvas position of a MAT's node.
    QPointF node_position(const QString& id) const;
    /// The MATs' id labels (some hidden where they would overlap) and where each is on screen.
    std::vector<const QGraphicsSimpleTextItem*> labels() const;
    /// The rate badges of the MATs off the audio rate (hidden where they would overlap).
    std::vector<const QGraphicsSimpleTextItem*> badges() const;
    QRectF label_on_screen(const QGraphicsSimpleTextItem& label) const;

  signals:
    void selection_changed(const QStringList& ids);

  protected:
    void mousePressEvent(QMouseEvent*) override;
    void mouseMoveEvent(QMouseEvent*) override;
    void mouseReleaseEvent(QMouseEvent*) override;
    void wheelEvent(QWheelEvent*) override;
    void resizeEvent(QResizeEvent*) override;
    void changeEvent(QEvent*) override;
    void keyPressEvent(QKeyEvent*) override;

  private:
    void rebuild();
    void add_finger(const Lia& finger, const std::map<std::string, QPointF>& at);
    void apply_zoom();
    void zoom_about(double scale, QPoint view_point);
    void fit_scene_rect();
    /// The node's id label and, off the audio rate, its rate badge (graph_view_labels.cpp).
    void add_labels(QGraphicsItem* node, const Mat& m, const Model& model);
    void thin_labels();
    void schedule_thin_labels();
    void scale_nodes();
    void pan_by(QPoint pixels);
    QRectF fitted_rect() const;
    double zoom_limited(double scale) const;
    QGraphicsItem* nearest_item(QPoint view_point) const;
    bool background_press(QMouseEvent* e);
    bool zoom_key(QKeyEvent* e);
    QString mat_at(QPointF scene_point) const;

    ModelDocument& document_;
    QGraphicsScene scene_;
    Tool tool_ = Tool::Select;
    MatKind mat_kind_ = MatKind::Mass;
    LiaKind link_kind_ = LiaKind::Spring;
    QString connect_from_;
    QGraphicsLineItem* rubber_line_ = nullptr;
    std::optional<QPointF> drag_start_;
    bool panning_ = false;
    bool panned_ = false;  ///< the background drag moved the view (else it was a click)
    bool fitting_ = true;  ///< follows the view's size until the user zooms or pans
    bool thin_labels_pending_ = false;
    std::vector<QGraphicsSimpleTextItem*> labels_;  ///< the MATs' ids
    std::vector<LabelSide> label_sides_;            ///< where each id stands by its node
    std::vector<std::size_t> label_nodes_;          ///< and its node, in nodes_
    std::vector<QGraphicsSimpleTextItem*> badges_;  ///< their rate levels, where not audio
    std::vector<std::size_t> badge_labels_;         ///< each badge's node's id, in labels_
    std::vector<double> badge_lifts_;    ///< px each badge stands over its place (past the id)
    std::vector<QGraphicsItem*> nodes_;  ///< MATs and bow modules, kept a least size on screen
    QRectF graph_bounds_;                ///< the nodes and links, labels left out
    QPoint pan_last_;
};

}  // namespace archet::ui
