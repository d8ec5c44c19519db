#pragma once
// The bowing maps of the open model side by side as tabs of one window: Playability (steady
// bowing, the Schelleng diagram) and Attack (how a note starts, the Guettler diagram). Each
// computes in the background; the window stays with the studio so its maps outlive a close
// (a sweep still running stops there: it would compete with the live engine for every core).

#include <QDialog>
#include <functional>
#include <optional>

#include "archet/model/model.hpp"

class QTabWidget;

namespace archet::ui {

class AttackPanel;
class PlayabilityPanel;

class BowingMapsWindow : public QDialog {
    Q_OBJECT

  public:
    enum class Tab { Playability, Attack };

    /// `gesture_point` says where the player bows now: (β, force), if anywhere.
    BowingMapsWindow(const Model& model,
                     std::function<std::optional<std::pair<double, double>>()> gesture_point,
                     QWidget* parent = nullptr);

    /// Brings the window up on `tab`.
    void show_tab(Tab tab);
    Tab current_tab() const;
    /// The open model changed: the next Compute of either tab maps this one.
    void set_model(const Model& model);
    PlayabilityPanel& playability() { return *playability_; }
    AttackPanel& attack() { return *attack_; }
    /// Closing the window (or Escape) stops a sweep under way; the maps drawn stay.
    void reject() override;

  private:
    QTabWidget* tabs_;
    PlayabilityPanel* playability_;
    AttackPanel* attack_;
};

}  // namespace archet::ui
