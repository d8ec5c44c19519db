#include "archet/ui/main_window.hpp"

#include <QAction>
#include <QDateTime>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QMessageBox>
#include <QSplitter>
#include <QStandardPaths>
#include <QStatusBar>
#include <QToolBar>
#include <QVBoxLayout>
#include <set>

#include "archet/bowed_string.hpp"
#include "archet/compiled_model.hpp"
#include "archet/model_file.hpp"
#include "archet/model_validation.hpp"
#include "archet/ui/gesture_pad.hpp"
#include "archet/ui/new_string_dialog.hpp"
#include "archet/ui/scope_panel.hpp"

namespace archet::ui {

namespace {
constexpr double kScopeRate = 48000;  // the engine's master clock (its --rate)
constexpr int kDisplayMs = 33;        // scopes at 30 frames a second
}  // namespace

MainWindow::MainWindow(EngineClientOptions options, QWidget* parent) : QMainWindow(parent) {
    setWindowTitle(tr("Archet studio"));
    engine_ = new EngineClient(std::move(options), this);
    scopes_ = new ScopePanel;
    pad_ = new GesturePad;
    summary_ = new QLabel;
    summary_->setWordWrap(true);
    summary_->setTextInteractionFlags(Qt::TextSelectableByMouse);

    auto* side = new QWidget;
    auto* side_layout = new QVBoxLayout(side);
    auto* pad_title = new QLabel(tr("<b>Gesture pad</b> — drag across to bow, down to press"));
    side_layout->addWidget(pad_title);
    side_layout->addWidget(pad_, 2);
    side_layout->addWidget(summary_, 1);
    auto* split = new QSplitter;
    split->addWidget(scopes_);
    split->addWidget(side);
    split->setStretchFactor(0, 3);
    split->setStretchFactor(1, 1);
    setCentralWidget(split);

    engine_state_ = new QLabel;
    device_ = new QLabel;
    meters_ = new QLabel;
    statusBar()->addPermanentWidget(engine_state_);
    statusBar()->addPermanentWidget(device_, 1);
    statusBar()->addPermanentWidget(meters_);
    build_actions();

    takes_folder_ =
        QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation) + "/Archet/takes";
    connect(pad_, &GesturePad::moved, engine_, &EngineClient::gesture);
    connect(engine_, &EngineClient::status_changed, this, &MainWindow::show_status);
    connect(engine_, &EngineClient::message, this,
            [this](const QString& text) { statusBar()->showMessage(text, 8000); });
    connect(engine_, &EngineClient::engine_lost, this,
            [this](const QString& why) { statusBar()->showMessage(why, 10000); });
    connect(&display_, &QTimer::timeout, this, &MainWindow::refresh);
    engine_->start();
    display_.start(kDisplayMs);
    resize(1280, 800);
}

void MainWindow::build_actions() {
    auto* bar = addToolBar(tr("Studio"));
    bar->setObjectName("studio");
    auto add = [&](const QString& text, QKeySequence keys, auto slot) {
        auto* action = bar->addAction(text);
        action->setShortcut(keys);
        connect(action, &QAction::triggered, this, slot);
        return action;
    };
    add(tr("New string…"), QKeySequence::New, &MainWindow::new_string);
    add(tr("Open…"), QKeySequence::Open, &MainWindow::open_dialog);
    add(tr("Save as…"), QKeySequence::SaveAs, &MainWindow::save_as);
    bar->addSeparator();
    play_ = add(tr("Play"), QKeySequence(Qt::Key_Space), &MainWindow::toggle_play);
    record_ = add(tr("Record take"), QKeySequence(Qt::Key_R), &MainWindow::toggle_take);
    auto* freeze = add(tr("Freeze scopes"), QKeySequence(Qt::Key_F),
                       [this] { scopes_->set_frozen(!scopes_->frozen()); });
    freeze->setToolTip(tr("Hold the scopes still to read them (F)"));
    add(tr("Quit"), QKeySequence::Quit, &QWidget::close);
}

namespace {
// The engine's shape frames list the MATs of the fastest level in model order; the string is
// those that are not part of a bow module (bow, pressure mass, surface).
std::vector<int> string_points(const Model& model) {
    std::set<std::string> bow_parts;
    for (const auto& l : model.lias)
        if (l.kind == LiaKind::BowFriction) bow_parts.insert({l.from, l.press, l.surface});
    const CompiledModel compiled = compile(model);
    std::vector<int> points;
    int entry = 0;
    for (const auto& m : model.mats) {
        if (compiled.mat_slots.at(m.id).level != 0) continue;
        if (!bow_parts.count(m.id)) points.push_back(entry);
        ++entry;
    }
    return points;
}
}  // namespace

void MainWindow::open_model(const Model& model, const QString& path) {
    model_ = model;
    path_ = path;
    string_points_ = string_points(model_);
    engine_->load(model_);
    setWindowTitle(tr("%1 — Archet studio").arg(QString::fromStdString(model_.name)));
    summary_->setText(
        tr("<b>%1</b><br>%2<br>%3 masses, %4 links; %5")
            .arg(QString::fromStdString(model_.name), QString::fromStdString(model_.description))
            .arg(model_.mats.size())
            .arg(model_.lias.size())
            .arg(path.isEmpty() ? tr("not saved yet") : path));
    if (!engine_->playing()) toggle_play();
}

bool MainWindow::open_file(const QString& path) {
    try {
        Model model = load_model_file(path.toStdString());
        validate_model(model);
        open_model(model, path);
        return true;
    } catch (const std::exception& e) {
        QMessageBox::warning(this, tr("Cannot open the model"), QString::fromUtf8(e.what()));
        return false;
    }
}

void MainWindow::new_string() {
    NewStringDialog dialog(this);
    if (dialog.exec() != QDialog::Accepted) return;
    try {
        open_model(build_bowed_string(dialog.options()));
    } catch (const std::exception& e) {
        QMessageBox::warning(this, tr("Cannot build that string"), QString::fromUtf8(e.what()));
    }
}

void MainWindow::open_dialog() {
    const QString path = QFileDialog::getOpenFileName(
        this, tr("Open a model"), QFileInfo(path_).path(), tr("Archet models (*.json)"));
    if (!path.isEmpty()) open_file(path);
}

void MainWindow::save_as() {
    QString path = QFileDialog::getSaveFileName(this, tr("Save the model"), path_,
                                                tr("Archet models (*.json)"));
    if (path.isEmpty()) return;
    if (!path.endsWith(".json")) path += ".json";
    try {
        write_file_atomically(path.toStdString(), format_model(model_));
        path_ = path;
        statusBar()->showMessage(tr("saved %1").arg(path), 5000);
    } catch (const std::exception& e) {
        QMessageBox::warning(this, tr("Cannot save"), QString::fromUtf8(e.what()));
    }
}

void MainWindow::toggle_play() {
    if (engine_->playing()) {
        engine_->stop();
        play_->setText(tr("Play"));
    } else {
        engine_->play();
        play_->setText(tr("Stop"));
    }
}

void MainWindow::toggle_take() {
    if (!take_.isEmpty()) {
        engine_->stop_take();
        statusBar()->showMessage(tr("finishing the take in %1").arg(take_), 5000);
        take_.clear();
        record_->setText(tr("Record take"));
        return;
    }
    take_ = takes_folder_ + "/" + QDateTime::currentDateTime().toString("yyyy-MM-dd-HHmmss-zzz");
    QDir().mkpath(take_);
    engine_->start_take(take_);
    record_->setText(tr("Stop recording"));
}

void MainWindow::refresh() {
    scopes_->refresh(engine_->history(), engine_->shape(), string_points_, kScopeRate);
    const ProbeHistory& h = engine_->history();
    pad_->set_feedback(h.latest(h.channel("hand_force_slide")),
                       h.latest(h.channel("hand_force_press")));
}

void MainWindow::show_status() {
    const EngineStatus& s = engine_->status();
    engine_state_->setText(tr("engine: %1").arg(s.state));
    device_->setText(s.device);
    meters_->setText(tr("xruns %1   load %2 %   energy %3 mJ%4")
                         .arg(s.xruns)
                         .arg(100 * s.load, 0, 'f', 1)
                         .arg(1000 * s.energy, 0, 'f', 3)
                         .arg(s.restarts ? tr("   restarts %1").arg(s.restarts) : QString()));
}

}  // namespace archet::ui
