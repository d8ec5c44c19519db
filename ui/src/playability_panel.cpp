#include "archet/ui/playability_panel.hpp"

#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QTimer>
#include <QVBoxLayout>

#include "archet/common/number_text.hpp"
#include "archet/common/parallel_for.hpp"
#include "archet/ui/playability_figure.hpp"
#include "archet/ui/sweep_form.hpp"

namespace archet::ui {

PlayabilityPanel::PlayabilityPanel(
    const Model& model, std::function<std::optional<std::pair<double, double>>()> gesture_point,
    QWidget* parent)
    : QWidget(parent), model_(model), gesture_point_(std::move(gesture_point)) {
    const MapGrid d;
    force_min_ = number_box(1e-4, 10, 0.002, 4, tr(" N"));
    force_max_ = number_box(1e-4, 10, 2.0, 3, tr(" N"));
    force_steps_ = count_box(1, 60, 12);
    position_min_ = number_box(0.01, 0.49, 0.05, 3, {});
    position_max_ = number_box(0.01, 0.49, 0.25, 3, {});
    position_steps_ = count_box(1, 40, 8);
    speed_ = number_box(0.005, 2, d.speed, 3, tr(" m/s"));
    duration_ = number_box(0.2, 10, d.duration, 2, tr(" s"));
    const SweepButtons buttons = sweep_buttons(job_, this);
    compute_ = buttons.compute, cancel_button_ = buttons.cancel, progress_ = buttons.progress;
    message_ = new QLabel(tr("A steady stroke on every point; click a point to hear it."));
    message_->setWordWrap(true);
    figure_ = new PlayabilityFigure;
    refresh_ = new QTimer(this);

    auto* ranges = new QFormLayout;
    ranges->addRow(tr("Bow force (log steps)"), range_row(force_min_, force_max_, force_steps_));
    ranges->addRow(tr("Bow position β"), range_row(position_min_, position_max_, position_steps_));
    auto* speed_row = new QHBoxLayout;
    speed_row->addWidget(speed_), speed_row->addWidget(new QLabel(tr("for"))),
        speed_row->addWidget(duration_);
    ranges->addRow(tr("Bow speed"), speed_row);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(ranges);
    layout->addLayout(buttons.row);
    layout->addWidget(message_);
    layout->addWidget(figure_, 1);
    connect(compute_, &QPushButton::clicked, this, &PlayabilityPanel::compute);
    connect(cancel_button_, &QPushButton::clicked, this, &PlayabilityPanel::cancel);
    connect(figure_, &PlayabilityFigure::point_clicked, this, &PlayabilityPanel::listen);
    // The player's bow moves while the map is shown: its cross follows.
    connect(refresh_, &QTimer::timeout, this, [this] {
        if (!map_.points.empty() && isVisible())
            figure_->mark(gesture_point_ ? gesture_point_() : std::nullopt);
    });
    refresh_->start(200);
}

void PlayabilityPanel::set_model(const Model& model) {
    model_ = model;
    ++freshness_.model;
    if (!map_.points.empty() && !busy()) message_->setText(model_changed_text());
}

void PlayabilityPanel::set_grid(const MapGrid& g) {
    force_min_->setValue(g.force_min), force_max_->setValue(g.force_max);
    force_steps_->setValue(g.force_steps);
    position_min_->setValue(g.position_min), position_max_->setValue(g.position_max);
    position_steps_->setValue(g.position_steps);
    speed_->setValue(g.speed), duration_->setValue(g.duration);
}

MapGrid PlayabilityPanel::grid_from_fields() const {
    MapGrid g;
    g.force_min = force_min_->value(), g.force_max = std::max(force_max_->value(), g.force_min);
    g.force_steps = force_steps_->value();
    g.position_min = position_min_->value();
    g.position_max = std::max(position_max_->value(), g.position_min);
    g.position_steps = position_steps_->value();
    g.speed = speed_->value(), g.duration = duration_->value();
    return g;
}

void PlayabilityPanel::compute() {
    if (busy()) return;
    const MapGrid grid = grid_from_fields();
    progress_->setMaximum(static_cast<int>(grid.size()));
    progress_->setValue(0);
    compute_->setEnabled(false), cancel_button_->setEnabled(true);
    message_->setText(tr("computing %1 on every core…")
                          .arg(QString::fromStdString(count_of(grid.size(), "point", "points"))));
    job_.start(
        [model = model_, grid](BackgroundJob::Control& control) {
            const int cores = hardware_jobs();
            return play_map(
                model, grid, cores, 0, 1,
                [&control](std::size_t done, std::size_t total) { control.progress(done, total); },
                &control.cancel_flag());
        },
        // Clicks play points of the grid the figure shows, which changes only now.
        [this, grid, model = model_, edit = freshness_.model](PlayedMap map) {
            grid_ = grid, shown_model_ = model, freshness_.shown = edit;
            finished(std::move(map), {});
        },
        [this](const QString& error) { finished({}, error); });
}

void PlayabilityPanel::finished(PlayedMap map, QString error) {
    compute_->setEnabled(true), cancel_button_->setEnabled(false);
    if (!error.isEmpty()) {
        message_->setText(error);
    } else {
        map_ = std::move(map);
        figure_->show_map(grid_, map_.points, map_.lines);
        figure_->mark(gesture_point_ ? gesture_point_() : std::nullopt);
        const HelmholtzPitch pitch = helmholtz_pitch(map_.points);
        const QString flattening =
            pitch.points == 0 ? QString()
                              : tr(", playing %1 to %2 cents against the string's first mode")
                                    .arg(pitch.flattest, 0, 'f', 1)
                                    .arg(pitch.sharpest, 0, 'f', 1);
        message_->setText(
            freshness_.note(tr("%1 of %2 points in Helmholtz motion%3; the cross is where you "
                               "bow now. Click a point to hear it.")
                                .arg(pitch.points)
                                .arg(map_.points.size())
                                .arg(flattening)));
    }
    emit computed(error);
}

void PlayabilityPanel::listen(long index) {
    if (index < 0 || static_cast<std::size_t>(index) >= map_.points.size()) return;
    try {
        std::vector<double> sound;
        const MapPoint p = play_map_point(shown_model_, grid_, static_cast<std::size_t>(index),
                                          map_.first_mode, &sound);
        player_.play(sound, shown_model_.sample_rate);
        message_->setText(
            freshness_.note(tr("β %1, %2 N: %3 (%4 slips per period, %5 cents) — playing on %6")
                                .arg(p.position, 0, 'f', 3)
                                .arg(p.force, 0, 'g', 3)
                                .arg(regime_name(p.analysis.regime))
                                .arg(p.analysis.slips_per_period, 0, 'f', 2)
                                .arg(p.analysis.pitch_cents, 0, 'f', 1)
                                .arg(QString::fromStdString(player_.description()))));
    } catch (const std::exception& e) {
        message_->setText(QString::fromUtf8(e.what()));
    }
}

}  // namespace archet::ui
