#include "archet/ui/attack_panel.hpp"

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

#include "archet/common/number_text.hpp"
#include "archet/common/parallel_for.hpp"
#include "archet/ui/attack_figure.hpp"
#include "archet/ui/sweep_form.hpp"

namespace archet::ui {

AttackPanel::AttackPanel(const Model& model, QWidget* parent) : QWidget(parent), model_(model) {
    const AttackGrid d;
    acceleration_min_ = number_box(0.01, 1000, d.acceleration_min, 2, tr(" m/s²"));
    acceleration_max_ = number_box(0.01, 1000, d.acceleration_max, 2, tr(" m/s²"));
    acceleration_steps_ = count_box(1, 60, d.acceleration_steps);
    force_min_ = number_box(1e-4, 100, d.force_min, 4, tr(" N"));
    force_max_ = number_box(1e-4, 100, d.force_max, 3, tr(" N"));
    force_steps_ = count_box(1, 60, d.force_steps);
    periods_max_ = count_box(1, 1000, d.periods_max);
    log_axes_ = new QCheckBox(tr("logarithmic steps and axes"));
    log_axes_->setChecked(d.log_axes);
    const SweepButtons buttons = sweep_buttons(job_, this);
    compute_ = buttons.compute, cancel_button_ = buttons.cancel, progress_ = buttons.progress;
    message_ = new QLabel(
        tr("The bow presses for 50 ms, then the hand accelerates steadily; each point counts the "
           "periods until Helmholtz motion. Click a point to hear its attack."));
    message_->setWordWrap(true);
    figure_ = new AttackFigure;

    auto* ranges = new QFormLayout;
    ranges->addRow(tr("Acceleration of the hand"),
                   range_row(acceleration_min_, acceleration_max_, acceleration_steps_));
    ranges->addRow(tr("Bow force"), range_row(force_min_, force_max_, force_steps_));
    auto* counting = new QHBoxLayout;
    counting->addWidget(periods_max_), counting->addWidget(new QLabel(tr("periods at most"))),
        counting->addStretch(), counting->addWidget(log_axes_);
    ranges->addRow(tr("Transient counted up to"), counting);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(ranges);
    layout->addLayout(buttons.row);
    layout->addWidget(message_);
    layout->addWidget(figure_, 1);
    connect(compute_, &QPushButton::clicked, this, &AttackPanel::compute);
    connect(cancel_button_, &QPushButton::clicked, this, &AttackPanel::cancel);
    connect(figure_, &AttackFigure::point_clicked, this, &AttackPanel::listen);
}

void AttackPanel::set_model(const Model& model) {
    model_ = model;
    ++freshness_.model;
    if (!points_.empty() && !busy()) message_->setText(model_changed_text());
}

void AttackPanel::set_grid(const AttackGrid& g) {
    acceleration_min_->setValue(g.acceleration_min);
    acceleration_max_->setValue(g.acceleration_max);
    acceleration_steps_->setValue(g.acceleration_steps);
    force_min_->setValue(g.force_min), force_max_->setValue(g.force_max);
    force_steps_->setValue(g.force_steps);
    periods_max_->setValue(g.periods_max);
    log_axes_->setChecked(g.log_axes);
}

AttackGrid AttackPanel::grid_from_fields() const {
    AttackGrid g;
    g.acceleration_min = acceleration_min_->value();
    g.acceleration_max = std::max(acceleration_max_->value(), g.acceleration_min);
    g.acceleration_steps = acceleration_steps_->value();
    g.force_min = force_min_->value(), g.force_max = std::max(force_max_->value(), g.force_min);
    g.force_steps = force_steps_->value();
    g.periods_max = periods_max_->value();
    g.log_axes = log_axes_->isChecked();
    return g;
}

void AttackPanel::compute() {
    if (busy()) return;
    const AttackGrid grid = grid_from_fields();
    progress_->setMaximum(static_cast<int>(grid.size()));
    progress_->setValue(0);
    compute_->setEnabled(false), cancel_button_->setEnabled(true);
    message_->setText(tr("computing %1 on every core…")
                          .arg(QString::fromStdString(count_of(grid.size(), "attack", "attacks"))));
    job_.start(
        [model = model_, grid](BackgroundJob::Control& control) {
            return play_attack(
                model, grid, hardware_jobs(), 0, 1,
                [&control](std::size_t done, std::size_t total) { control.progress(done, total); },
                &control.cancel_flag());
        },
        [this, model = model_, edit = freshness_.model](AttackMap map) {
            shown_model_ = model, freshness_.shown = edit;
            finished(std::move(map), {});
        },
        [this](const QString& error) { finished({}, error); });
}

void AttackPanel::finished(AttackMap map, QString error) {
    compute_->setEnabled(true), cancel_button_->setEnabled(false);
    if (!error.isEmpty()) {
        message_->setText(error);
    } else {
        // Clicks play points of the grid the figure shows, set only now.
        grid_ = map.grid, pitch_ = map.pitch;
        points_ = std::move(map.points);
        figure_->show_attacks(grid_, points_, QString::fromStdString(shown_model_.name));
        int perfect = 0;
        for (const auto& p : points_) perfect += p.transient.kind == AttackKind::Perfect;
        message_->setText(
            freshness_.note(tr("%1 of %2 attacks perfect (Helmholtz motion from the first slip). "
                               "Click a point to hear its attack.")
                                .arg(perfect)
                                .arg(points_.size())));
    }
    emit computed(error);
}

void AttackPanel::listen(long index) {
    if (index < 0 || static_cast<std::size_t>(index) >= points_.size()) return;
    try {
        std::vector<double> sound;
        const AttackPoint p =
            play_attack_point(shown_model_, grid_, static_cast<std::size_t>(index), pitch_, &sound);
        player_.play(sound, shown_model_.sample_rate);
        const QString length =
            p.transient.kind == AttackKind::Never
                ? tr("no Helmholtz motion in %1 periods").arg(grid_.periods_max)
                : tr("%1 periods to Helmholtz motion").arg(p.transient.periods, 0, 'f', 1);
        message_->setText(freshness_.note(tr("%1 m/s², %2 N: %3, %4 — playing on %5")
                                              .arg(p.acceleration, 0, 'g', 3)
                                              .arg(p.force, 0, 'g', 3)
                                              .arg(transient_name(p.transient.transient))
                                              .arg(length)
                                              .arg(QString::fromStdString(player_.description()))));
    } catch (const std::exception& e) {
        message_->setText(QString::fromUtf8(e.what()));
    }
}

}  // namespace archet::ui
