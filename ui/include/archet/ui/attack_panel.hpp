#pragma once
// The attack panel: the current model's attack map (Guettler diagram) computed in the
// background on every core, with progress and cancel, and a click on a point to hear its attack.

#include <QWidget>

#include "archet/analysis/attack.hpp"
#include "archet/model/model.hpp"
#include "archet/preview_player.hpp"
#include "archet/ui/background_job.hpp"
#include "archet/ui/sweep_form.hpp"

class QCheckBox;
class QDoubleSpinBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QSpinBox;

namespace archet::ui {

class AttackFigure;

class AttackPanel : public QWidget {
    Q_OBJECT

  public:
    explicit AttackPanel(const Model& model, QWidget* parent = nullptr);

    /// The model the next Compute maps; the map shown, and its points' sounds, stay those
    /// of the model it was computed for until then.
    void set_model(const Model& model);
    void set_grid(const AttackGrid& grid);
    void compute();
    void cancel() { job_.cancel(); }
    bool busy() const { return job_.busy(); }
    const std::vector<AttackPoint>& points() const { return points_; }
    AttackFigure& figure() { return *figure_; }
    PreviewPlayer& player() { return player_; }
    /// Plays the attack of grid point `index` again and lets it be heard.
    void listen(long index);

  signals:
    void computed(const QString& error);

  private:
    AttackGrid grid_from_fields() const;
    void finished(AttackMap map, QString error);

    Model model_;        ///< the open model, mapped by the next Compute
    Model shown_model_;  ///< the model the figure shows
    MapFreshness freshness_;
    AttackGrid grid_;   ///< the grid the figure shows
    double pitch_ = 0;  ///< the string's first mode its periods count
    QDoubleSpinBox *acceleration_min_, *acceleration_max_, *force_min_, *force_max_;
    QSpinBox *acceleration_steps_, *force_steps_, *periods_max_;
    QCheckBox* log_axes_;
    QPushButton *compute_, *cancel_button_;
    QProgressBar* progress_;
    QLabel* message_;
    AttackFigure* figure_;
    std::vector<AttackPoint> points_;
    PreviewPlayer player_;  ///< the preview path, apart from the engine
    BackgroundJob job_;     ///< last: destroyed (cancelled and joined) first
};

}  // namespace archet::ui
