#include "archet/ui/main_window.hpp"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QClipboard>
#include <QCloseEvent>
#include <QDateTime>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QSettings>
#include <QSplitter>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTabWidget>
#include <QToolBar>
#include <QUndoStack>
#include <QVBoxLayout>
#include <set>

#include "archet/bowed_string.hpp"
#include "archet/compiled_model.hpp"
#include "archet/model_file.hpp"
#include "archet/model_parameters.hpp"
#include "archet/model_validation.hpp"
#include "archet/playability.hpp"
#include "archet/ui/compare_view.hpp"
#include "archet/ui/gesture_pad.hpp"
#include "archet/ui/graph_view.hpp"
#include "archet/ui/inspector.hpp"
#include "archet/ui/library_panel.hpp"
#include "archet/ui/model_document.hpp"
#include "archet/ui/modes_panel.hpp"
#include "archet/ui/new_string_dialog.hpp"
#include "archet/ui/playability_panel.hpp"
#include "archet/ui/scope_panel.hpp"
#include "archet/ui/settings_dialog.hpp"
#include "archet/ui/sound_examples_dialog.hpp"
#include "archet/ui/takes_panel.hpp"
#include "archet/ui/widget_export.hpp"

namespace archet::ui {

namespace {
constexpr double kScopeRate = 48000;  // the engine's master clock (its --rate)
constexpr int kDisplayMs = 33;        // scopes at 30 frames a second
constexpr int kAutosaveMs = 30000;
constexpr int kRecentFiles = 8;

// The engine's shape frames list the MATs of the fastest level in model order; the string is
// those that are not part of a bow module (bow, pressure mass, surface).
std::vector<int> string_points(const Model& model) {
    std::set<std::string> bow_parts;
    for (const auto& l : model.lias)
        if (l.kind == LiaKind::BowFriction) bow_parts.insert({l.from, l.press, l.surface});
    std::vector<int> points;
    try {
        const CompiledModel compiled = compile(model);
        int entry = 0;
        for (const auto& m : model.mats) {
            if (compiled.mat_slots.at(m.id).level != 0) continue;
            if (!bow_parts.count(m.id)) points.push_back(entry);
            ++entry;
        }
    } catch (const std::exception&) {
        // A model being edited may not compile yet; the scope shows nothing until it does.
    }
    return points;
}
}  // namespace

MainWindow::MainWindow(EngineClientOptions options, QWidget* parent) : QMainWindow(parent) {
    engine_ = new EngineClient(std::move(options), this);
    document_ = new ModelDocument(this);
    graph_ = new GraphView(*document_);
    inspector_ = new Inspector(*document_);
    modes_ = new ModesPanel(*document_);
    scopes_ = new ScopePanel;
    pad_ = new GesturePad;
    takes_ = new TakesPanel;
    library_ = new LibraryPanel;

    auto* left = new QSplitter(Qt::Vertical);
    left->addWidget(graph_);
    left->addWidget(scopes_);
    left->setStretchFactor(0, 1);
    left->setStretchFactor(1, 3);
    auto* tabs = new QTabWidget;
    tabs->addTab(inspector_, tr("Inspector"));
    tabs->addTab(modes_, tr("Modes"));
    tabs->addTab(takes_, tr("Takes"));
    tabs->addTab(library_, tr("Library"));
    auto* side = new QWidget;
    auto* side_layout = new QVBoxLayout(side);
    side_layout->addWidget(
        new QLabel(tr("<b>Gesture pad</b> — drag across to bow, down to press")));
    side_layout->addWidget(pad_, 2);
    side_layout->addWidget(tabs, 3);
    auto* split = new QSplitter;
    split->addWidget(left);
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
    build_menus();
    addToolBar(Qt::LeftToolBarArea, build_palette());

    const QString documents = QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation);
    set_takes_folder(documents + "/Archet/takes");
    autosave_folder_ =
        QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + "/autosave";
    connect(pad_, &GesturePad::moved, engine_, &EngineClient::gesture);
    connect(library_, &LibraryPanel::open_requested, this,
            [this](const QString& p) { open_file(p); });
    connect(library_, &LibraryPanel::new_string_requested, this, &MainWindow::new_string);
    connect(graph_, &GraphView::selection_changed, this, [this](const QStringList& ids) {
        inspector_->show_element(ids.size() == 1 ? ids.front() : QString());
    });
    connect(document_, &ModelDocument::changed, this,
            [this](ModelDocument::Change change, const QString& element, const QString& name) {
                model_changed(static_cast<int>(change), element, name);
            });
    connect(document_, &ModelDocument::path_changed, this, [this] { update_title(); });
    connect(&document_->undo_stack(), &QUndoStack::cleanChanged, this, [this] { update_title(); });
    connect(engine_, &EngineClient::status_changed, this, &MainWindow::show_status);
    connect(engine_, &EngineClient::message, this, [this](const QString& text) {
        statusBar()->showMessage(text, 8000);
        if (text.startsWith("take written")) takes_->refresh();
    });
    connect(engine_, &EngineClient::engine_lost, this,
            [this](const QString& why) { statusBar()->showMessage(why, 10000); });
    connect(&display_, &QTimer::timeout, this, &MainWindow::refresh);
    connect(&autosave_timer_, &QTimer::timeout, this, [this] {
        if (document_->modified()) autosave();
    });
    engine_->start();
    display_.start(kDisplayMs);
    autosave_timer_.start(kAutosaveMs);
    resize(1400, 900);
}

// The children go after this window's own part is gone; none of them may call back into it.
MainWindow::~MainWindow() {
    for (QObject* source : std::initializer_list<QObject*>{document_, &document_->undo_stack(),
                                                           engine_, graph_, library_, pad_})
        disconnect(source, nullptr, this, nullptr);
}

void MainWindow::build_menus() {
    auto action = [this](QMenu* menu, const QString& text, QKeySequence keys, auto slot) {
        QAction* a = menu->addAction(text);
        a->setShortcut(keys);
        connect(a, &QAction::triggered, this, slot);
        return a;
    };
    QMenu* file = menuBar()->addMenu(tr("&File"));
    action(file, tr("&New bowed string…"), QKeySequence::New, &MainWindow::new_string);
    action(file, tr("&Open…"), QKeySequence::Open, &MainWindow::open_dialog);
    recent_ = file->addMenu(tr("Open &recent"));
    fill_recent_menu();
    action(file, tr("&Save"), QKeySequence::Save, &MainWindow::save);
    action(file, tr("Save &as…"), QKeySequence::SaveAs, &MainWindow::save_as);
    file->addSeparator();
    action(file, tr("Render sound &examples…"), QKeySequence(), [this] {
        auto* dialog = new SoundExamplesDialog(
            resources_folder_,
            QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation) +
                "/Archet/sound-examples",
            this);
        dialog->setAttribute(Qt::WA_DeleteOnClose);
        dialog->show();
    });
    file->addSeparator();
    action(file, tr("&Quit"), QKeySequence::Quit, &QWidget::close);

    QMenu* edit = menuBar()->addMenu(tr("&Edit"));
    QAction* undo = document_->undo_stack().createUndoAction(this, tr("&Undo"));
    undo->setShortcut(QKeySequence::Undo);
    QAction* redo = document_->undo_stack().createRedoAction(this, tr("&Redo"));
    redo->setShortcut(QKeySequence::Redo);
    edit->addAction(undo);
    edit->addAction(redo);
    edit->addSeparator();
    action(edit, tr("&Copy"), QKeySequence::Copy, &MainWindow::copy);
    action(edit, tr("&Paste"), QKeySequence::Paste, &MainWindow::paste);
    action(edit, tr("&Delete"), QKeySequence::Delete, [this] {
        if (!graph_->selected_ids().isEmpty()) document_->remove(graph_->selected_ids());
    });

    QMenu* view = menuBar()->addMenu(tr("&View"));
    action(view, tr("&Fit the graph"), QKeySequence(Qt::CTRL | Qt::Key_0),
           [this] { graph_->fit(); });
    action(view, tr("F&reeze scopes"), QKeySequence(Qt::Key_F),
           [this] { scopes_->set_frozen(!scopes_->frozen()); });
    action(view, tr("&Export scopes…"), QKeySequence(Qt::CTRL | Qt::Key_E), [this] {
        const QString path = QFileDialog::getSaveFileName(this, tr("Export the scopes"),
                                                          "scopes.png", tr("Images (*.png *.pdf)"));
        if (!path.isEmpty() && !save_widget_image(*scopes_, path))
            statusBar()->showMessage(tr("could not write %1").arg(path), 8000);
    });

    QMenu* play = menuBar()->addMenu(tr("&Play"));
    play_ = action(play, tr("&Play"), QKeySequence(Qt::Key_Space), &MainWindow::toggle_play);
    record_ = action(play, tr("&Record take"), QKeySequence(Qt::Key_R), &MainWindow::toggle_take);
    play->addSeparator();
    action(play, tr("Audio and &devices…"), QKeySequence(), [this] {
        SettingsDialog dialog(engine_->options(), this);
        if (dialog.exec() == QDialog::Accepted) engine_->reconfigure(dialog.options());
    });
    action(play, tr("Playa&bility map…"), QKeySequence(Qt::CTRL | Qt::Key_M), [this] {
        // Where the player bows now: the model's bow position, the pad's press as a force.
        auto here = [this]() -> std::optional<std::pair<double, double>> {
            try {
                const double force = force_for_press(document_->model(), pad_->press());
                if (force <= 0) return std::nullopt;
                return std::make_pair(bow_position(document_->model()), force);
            } catch (const std::exception&) {
                return std::nullopt;
            }
        };
        auto* panel = new PlayabilityPanel(document_->model(), here, this);
        panel->setAttribute(Qt::WA_DeleteOnClose);
        panel->show();
    });
    action(play, tr("&Compare settings…"), QKeySequence(Qt::CTRL | Qt::Key_K), [this] {
        auto* view = new CompareView(document_->model(), this);
        view->setAttribute(Qt::WA_DeleteOnClose);
        view->show();
    });

    auto* bar = addToolBar(tr("Transport"));
    bar->setObjectName("transport");
    bar->addAction(play_);
    bar->addAction(record_);
    bar->addSeparator();
    bar->addAction(undo);
    bar->addAction(redo);
}

QToolBar* MainWindow::build_palette() {
    auto* bar = new QToolBar(tr("Palette"));
    bar->setObjectName("palette");
    bar->setToolButtonStyle(Qt::ToolButtonTextOnly);
    auto* group = new QActionGroup(bar);
    auto tool = [&](const QString& text, const QString& tip, auto choose) {
        QAction* a = bar->addAction(text);
        a->setCheckable(true);
        a->setToolTip(tip);
        group->addAction(a);
        connect(a, &QAction::triggered, this, choose);
        return a;
    };
    using Tool = GraphView::Tool;
    tool(tr("Select"), tr("Select, drag to move, rubber band for several (Esc)"), [this] {
        graph_->set_tool(Tool::Select);
    })->setChecked(true);
    bar->addSeparator();
    tool(tr("Mass"), tr("Click the canvas to place a mass"),
         [this] { graph_->set_tool(Tool::AddMat, MatKind::Mass); });
    tool(tr("Fixed"), tr("Click the canvas to place a fixed point"),
         [this] { graph_->set_tool(Tool::AddMat, MatKind::Fixed); });
    tool(tr("Oscillator"), tr("Click the canvas to place a mass on a spring to ground"),
         [this] { graph_->set_tool(Tool::AddMat, MatKind::Oscillator); });
    tool(tr("Hand"), tr("Click the canvas to place a gesture point (a device axis)"),
         [this] { graph_->set_tool(Tool::AddMat, MatKind::Gesture); });
    bar->addSeparator();
    tool(tr("Spring"), tr("Drag from one mass to another to join them with a spring"),
         [this] { graph_->set_tool(Tool::Connect, MatKind::Mass, LiaKind::Spring); });
    tool(tr("Damper"), tr("Drag from one mass to another to join them with a damper"),
         [this] { graph_->set_tool(Tool::Connect, MatKind::Mass, LiaKind::Damper); });
    tool(tr("Spring-damper"), tr("Drag from one mass to another: a visco-elastic link"),
         [this] { graph_->set_tool(Tool::Connect, MatKind::Mass, LiaKind::SpringDamper); });
    tool(tr("Buffer"), tr("Drag from one mass to another: a contact that only pushes"),
         [this] { graph_->set_tool(Tool::Connect, MatKind::Mass, LiaKind::Buffer); });
    return bar;
}

void MainWindow::set_takes_folder(const QString& folder) {
    takes_folder_ = folder;
    takes_->set_folder(folder);
}

void MainWindow::set_resources_folder(const QString& folder) {
    resources_folder_ = folder;
    library_->fill(folder + "/models", QSettings().value("recent").toStringList(),
                   autosave_folder_);
}

void MainWindow::open_model(const Model& model, const QString& path) {
    document_->reset(model, path);
    graph_->fit();
    if (!engine_->playing()) toggle_play();
}

bool MainWindow::open_file(const QString& path) {
    try {
        Model model = load_model_file(path.toStdString());
        validate_model(model);
        open_model(model, path);
        remember_recent(path);
        return true;
    } catch (const std::exception& e) {
        QMessageBox::warning(this, tr("Cannot open the model"), QString::fromUtf8(e.what()));
        return false;
    }
}

bool MainWindow::save_to(const QString& path) {
    try {
        write_file_atomically(path.toStdString(), format_model(document_->model()));
        document_->set_path(path);
        document_->mark_saved();
        remember_recent(path);
        statusBar()->showMessage(tr("saved %1").arg(path), 5000);
        return true;
    } catch (const std::exception& e) {
        QMessageBox::warning(this, tr("Cannot save"), QString::fromUtf8(e.what()));
        return false;
    }
}

QString MainWindow::autosave() {
    QDir().mkpath(autosave_folder_);
    const QString name = QString::fromStdString(document_->model().name);
    const QString path =
        QDir(autosave_folder_).filePath((name.isEmpty() ? "untitled" : name) + ".json");
    try {
        write_file_atomically(path.toStdString(), format_model(document_->model()));
        statusBar()->showMessage(tr("autosaved to %1").arg(path), 3000);
    } catch (const std::exception& e) {
        statusBar()->showMessage(tr("autosave failed: %1").arg(QString::fromUtf8(e.what())), 8000);
    }
    return path;
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
    const QString path =
        QFileDialog::getOpenFileName(this, tr("Open a model"), QFileInfo(document_->path()).path(),
                                     tr("Archet models (*.json)"));
    if (!path.isEmpty()) open_file(path);
}

void MainWindow::save() {
    if (document_->path().isEmpty()) return save_as();
    save_to(document_->path());
}

void MainWindow::save_as() {
    QString path = QFileDialog::getSaveFileName(this, tr("Save the model"), document_->path(),
                                                tr("Archet models (*.json)"));
    if (path.isEmpty()) return;
    if (!path.endsWith(".json")) path += ".json";
    save_to(path);
}

void MainWindow::closeEvent(QCloseEvent* e) {
    if (document_->modified()) {
        const auto answer =
            QMessageBox::question(this, tr("Unsaved changes"),
                                  tr("Save the changes to %1 before closing?")
                                      .arg(QString::fromStdString(document_->model().name)),
                                  QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel);
        if (answer == QMessageBox::Cancel) return e->ignore();
        if (answer == QMessageBox::Save) {
            save();
            if (document_->modified()) return e->ignore();
        }
    }
    e->accept();
}

void MainWindow::copy() {
    const QStringList ids = graph_->selected_ids();
    if (!ids.isEmpty()) QApplication::clipboard()->setText(document_->copy(ids));
}

void MainWindow::paste() {
    const QStringList added = document_->paste(QApplication::clipboard()->text(), {40, 40});
    if (!added.isEmpty()) graph_->select(added);
}

// The engine follows the document: a parameter glides in, anything else reloads the model.
// A model that does not validate stays in the editor (the engine keeps the last good one).
void MainWindow::model_changed(int change, const QString& element, const QString& parameter) {
    update_title();
    if (static_cast<ModelDocument::Change>(change) == ModelDocument::Change::Layout) return;
    const Model& model = document_->model();
    try {
        validate_model(model);
    } catch (const std::exception& e) {
        statusBar()->showMessage(tr("not played yet: %1").arg(QString::fromUtf8(e.what())), 10000);
        return;
    }
    if (static_cast<ModelDocument::Change>(change) == ModelDocument::Change::Parameter) {
        engine_->set_parameter(
            element + "." + parameter,
            get_parameter(model, element.toStdString(), parameter.toStdString()));
        return;
    }
    string_points_ = string_points(model);
    engine_->load(model);
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
        return;
    }
    take_ = takes_folder_ + "/" + QDateTime::currentDateTime().toString("yyyy-MM-dd-HHmmss-zzz");
    QDir().mkpath(take_);
    engine_->start_take(take_);
    record_->setText(tr("Stop &recording"));
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

void MainWindow::update_title() {
    const QString name = QString::fromStdString(document_->model().name);
    setWindowTitle(tr("%1%2 — Archet studio")
                       .arg(name.isEmpty() ? tr("untitled") : name,
                            document_->modified() ? QStringLiteral(" *") : QString()));
}

void MainWindow::remember_recent(const QString& path) {
    QSettings settings;
    QStringList recent = settings.value("recent").toStringList();
    recent.removeAll(path);
    recent.prepend(QFileInfo(path).absoluteFilePath());
    while (recent.size() > kRecentFiles) recent.removeLast();
    settings.setValue("recent", recent);
    fill_recent_menu();
    if (!resources_folder_.isEmpty())
        library_->fill(resources_folder_ + "/models", recent, autosave_folder_);
}

void MainWindow::fill_recent_menu() {
    recent_->clear();
    const QStringList recent = QSettings().value("recent").toStringList();
    for (const QString& path : recent)
        connect(recent_->addAction(QFileInfo(path).fileName()), &QAction::triggered, this,
                [this, path] { open_file(path); });
    recent_->setEnabled(!recent.isEmpty());
}

}  // namespace archet::ui
