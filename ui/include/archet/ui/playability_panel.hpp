#pragma once
// The playability panel: the current model's map (Schelleng diagram) computed in the
// background on every core, the current gesture's point on it, and a click on a run to hear it.

#include <QWidget>
#include <functional>
#include <optional>

#include "archet/analysis/playability.hpp"
#include "archet/model/model.hpp"
#include "archet/preview_player.hpp"
#include "archet/ui/background_job.hpp"
#include "archet/ui/sweep_form.hpp"

class QDoubleSpinBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QTimer;

namespace archet::ui {

class PlayabilityFigure;

class PlayabilityPanel : public QWidget {
    Q_OBJECT

  public:
    /// `gesture_point` says where the player bows now: (β, force), if anywhere.
    PlayabilityPanel(const Model& model,
                     std::function<std::optional<std::pair<double, double>>()> gesture_point,
                     QWidget* parent = nullptr);

    /// The model the next Compute maps; the map shown, and its points' sounds, stay those
    /// of the model it was computed for until then.
    void set_model(const Model& model);
    void set_grid(const MapGrid& grid);
    void compute();
    void cancel() { job_.cancel(); }
    bool busy() const { return job_.busy(); }
    const std::vector<MapPoint>& points() const { return map_.points; }
    PlayabilityFigure& figure() { return *figure_; }
    PreviewPlayer& player() { return player_; }
    /// Renders grid point `index` again on the GUI thread (one stroke: its pitch is measured
    /// against the map's first mode, with no modal analysis) and plays it.
    void listen(long index);

  signals:
    void computed(const QString& error);

  private:
    MapGrid grid_from_fields() const;
    void finished(PlayedMap map, QString error);

    Model model_;        ///< the open model, mapped by the next Compute
    Model shown_model_;  ///< the model the figure shows
    MapFreshness freshness_;
    MapGrid grid_;  ///< the grid the figure shows
    std::function<std::optional<std::pair<double, double>>()> gesture_point_;
    QDoubleSpinBox *force_min_, *force_max_, *position_min_, *position_max_, *speed_, *duration_;
    QSpinBox *force_steps_, *position_steps_;
    QPushButton *compute_, *cancel_button_;
    QProgressBar* progress_;
    QLabel* message_;
    PlayabilityFigure* figure_;
    QTimer* refresh_;
    PlayedMap map_;         ///< the map the figure shows
    PreviewPlayer player_;  ///< the preview path, apart from the engine
    BackgroundJob job_;     ///< last: destroyed (cancelled and joined) first
};

}  // namespace archet::ui
