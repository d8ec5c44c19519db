#include "archet/ui/main_window.hpp"

#include <QDateTime>
#include <QDir>
#include <QLabel>
#include <QStatusBar>
#include <algorithm>
#include <cmath>

#include "archet/analysis/playability.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/ui/elided_label.hpp"
#include "archet/ui/gesture_pad.hpp"
#include "archet/ui/model_document.hpp"
#include "archet/ui/recording_clock.hpp"
#include "archet/ui/scope_panel.hpp"
#include "archet/ui/takes_panel.hpp"

// The main window's live engine: the document's edits reach the running model, the pad bows
// it, play and takes start and stop it, and its state, device and meters are in the status bar.

namespace archet::ui {

namespace {
// What the pad can play on this model, when it cannot: said on the pad, not left silent.
QString unplayable_reason(const Model& model) {
    const bool hand = std::any_of(model.mats.begin(), model.mats.end(),
                                  [](const Mat& m) { return m.kind == MatKind::Gesture; });
    const bool bow = first_bow(model) != nullptr;
    if (!hand)
        return QObject::tr(
            "This model has no hand (gesture point): the pad has nothing to move. "
            "Add a Hand from the palette and link it to a mass.");
    if (!bow)
        return QObject::tr(
            "This model has no bow: the pad moves its hand, but nothing bows "
            "a string.");
    return {};
}
}  // namespace

void MainWindow::connect_engine() {
    connect(pad_, &GesturePad::moved, engine_, &EngineClient::gesture);
    connect(pad_, &GesturePad::note, this, &MainWindow::finger_to);
    connect(document_, &ModelDocument::changed, this,
            [this](ModelDocument::Change change, const QString& element, const QString& name) {
                model_changed(static_cast<int>(change), element, name);
            });
    connect(engine_, &EngineClient::status_changed, this, &MainWindow::show_status);
    // Edits are checked at the rate the engine's device runs the model at.
    connect(engine_, &EngineClient::status_changed, this,
            [this] { document_->set_running_rate(engine_->status().sample_rate); });
    connect(engine_, &EngineClient::message, this, [this](const QString& text) {
        // A take that clipped, was cut short or lost samples stays said: longer in the status bar,
        // and in the Takes tab until the next take's news.
        const bool take = text.startsWith("take ");
        const bool warning =
            text.contains("clipped") || text.contains("interrupted") || text.contains("incomplete");
        statusBar()->showMessage(text, take && warning ? 30000 : 8000);
        if (text.startsWith("take written")) takes_->refresh();
        if (take) takes_->show_note(text);
    });
    connect(engine_, &EngineClient::engine_lost, this,
            [this](const QString& why) { statusBar()->showMessage(why, 10000); });
    connect(&display_, &QTimer::timeout, this, &MainWindow::refresh);
}

// The engine follows the document: a parameter glides in, a moved bow takes the string's motion
// over, anything else reloads the model.
// A model that does not validate stays in the editor (the engine keeps the last good one).
// The document has already checked a parameter edit; only a new structure is validated here.
void MainWindow::model_changed(int change, const QString& element, const QString& name) {
    update_title();
    const auto kind = static_cast<ModelDocument::Change>(change);
    if (kind == ModelDocument::Change::Layout) return;
    const Model& model = document_->model();
    const bool parameter = kind == ModelDocument::Change::Parameter ||
                           kind == ModelDocument::Change::ReplayedParameter;
    auto glide = [&] {
        const ParameterName edited{element.toStdString(), name.toStdString()};
        engine_->send_parameter(edited, get_parameter(model, edited));
    };
    if (kind == ModelDocument::Change::Parameter && !engine_behind_) return glide();
    // The playing string goes on with its bow moved (undone, moved back).
    if (kind == ModelDocument::Change::BowMove && !engine_behind_)
        return engine_->send_parameter({"bow", "position"}, bow_position(model));
    if (!parameter) pad_->set_notice(unplayable_reason(model));
    try {
        document_->validate();  // a new structure, or a value that undo or redo brought back
    } catch (const std::exception& e) {
        engine_behind_ = true;
        statusBar()->showMessage(tr("Not played yet: %1").arg(QString::fromUtf8(e.what())), 10000);
        return;
    }
    if (parameter && !engine_behind_) return glide();
    engine_behind_ = false;
    engine_->load(model);
}

// A performance, not an edit: the engine's finger moves, the document (and its undo) stays.
// A take records the move like any parameter change.
void MainWindow::finger_to(int semitones) {
    const Lia* finger = first_finger(document_->model());
    if (!finger) {
        statusBar()->showMessage(
            tr("This string has no finger: build one with File → New bowed string… (Finger)"),
            5000);
        return;
    }
    const double position = semitones < 0 ? finger->finger_position : std::exp2(-semitones / 12.0);
    engine_->send_parameter({finger->id, "position"}, position);
}

void MainWindow::toggle_play() {
    if (engine_->playing()) {
        engine_->stop();
        play_->setText(tr("&Play"));
    } else {
        engine_->play();
        play_->setText(tr("S&top"));
    }
}

void MainWindow::toggle_take() {
    if (!take_.isEmpty()) {
        engine_->stop_take();
        statusBar()->showMessage(tr("finishing the take in %1").arg(take_), 5000);
        take_.clear();
        record_->setText(tr("&Record take"));
        recording_clock_->stop();
        return;
    }
    take_ = takes_folder_ + "/" + QDateTime::currentDateTime().toString("yyyy-MM-dd-HHmmss-zzz");
    QDir().mkpath(take_);
    engine_->start_take(take_);
    record_->setText(tr("Stop &recording"));
    recording_clock_->start();
}

void MainWindow::refresh() {
    const double rate = engine_->status().sample_rate;  // the engine's, once it says
    if (rate <= 0) return;
    scopes_->refresh(engine_->history(), engine_->shape(), engine_->shape_along(), rate);
    const ProbeHistory& h = engine_->history();
    pad_->set_feedback(h.latest(h.channel("hand_force_slide")),
                       h.latest(h.channel("hand_force_press")));
}

void MainWindow::show_status() {
    const EngineStatus& s = engine_->status();
    QString state = tr("engine: %1").arg(s.state);
    if (s.state == "running" && s.sample_rate > 0)
        state +=
            tr(" at %1 kHz").arg(s.sample_rate / 1000, 0, 'g', 4);  // the device says its block
    engine_state_->setText(state);
    QString device = s.device;
    if (s.restarts > 0)
        device = (s.restarts == 1 ? tr("The engine was restarted once: %1.").arg(s.last_restart)
                                  : tr("The engine was restarted %1 times, last: %2.")
                                        .arg(s.restarts)
                                        .arg(s.last_restart)) +
                 "  " + device;
    device_->set_full_text(device);
    meters_->setText(tr("xruns %1   load %2 %   energy %3 mJ")
                         .arg(s.xruns)
                         .arg(100 * s.load, 0, 'f', 1)
                         .arg(1000 * s.energy, 0, 'f', 3));
    meters_->setToolTip(
        tr("Load: the real-time thread's share of its time budget over the last 0.2 s "
           "(the longest block so far took %1 % of a block's period).")
            .arg(100 * s.worst_load, 0, 'f', 0));
}

}  // namespace archet::ui
