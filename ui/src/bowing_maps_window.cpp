#include "archet/ui/bowing_maps_window.hpp"

#include <QTabWidget>
#include <QVBoxLayout>

#include "archet/ui/attack_panel.hpp"
#include "archet/ui/playability_panel.hpp"

namespace archet::ui {

BowingMapsWindow::BowingMapsWindow(
    const Model& model, std::function<std::optional<std::pair<double, double>>()> gesture_point,
    QWidget* parent)
    : QDialog(parent) {
    setObjectName("bowing-maps");
    tabs_ = new QTabWidget;
    playability_ = new PlayabilityPanel(model, std::move(gesture_point));
    attack_ = new AttackPanel(model);
    tabs_->addTab(playability_, tr("Playability"));
    tabs_->addTab(attack_, tr("Attack"));
    tabs_->setTabToolTip(0, tr("Steady bowing over bow force and position (Schelleng diagram)"));
    tabs_->setTabToolTip(1, tr("How a note starts, over the bow's acceleration and force "
                               "(Guettler diagram)"));
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(tabs_);
    setWindowTitle(tr("Bowing maps — %1").arg(QString::fromStdString(model.name)));
    resize(1000, 860);
}

void BowingMapsWindow::show_tab(Tab tab) {
    tabs_->setCurrentIndex(tab == Tab::Playability ? 0 : 1);
    show();
    raise();
    activateWindow();
}

BowingMapsWindow::Tab BowingMapsWindow::current_tab() const {
    return tabs_->currentIndex() == 0 ? Tab::Playability : Tab::Attack;
}

void BowingMapsWindow::reject() {
    playability_->cancel();
    attack_->cancel();
    QDialog::reject();
}

void BowingMapsWindow::set_model(const Model& model) {
    setWindowTitle(tr("Bowing maps — %1").arg(QString::fromStdString(model.name)));
    playability_->set_model(model);
    attack_->set_model(model);
}

}  // namespace archet::ui
