#include "archet/ui/main_window.hpp"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QClipboard>
#include <QCloseEvent>
#include <QDateTime>
#include <QDesktopServices>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QScrollArea>
#include <QSettings>
#include <QSplitter>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTabWidget>
#include <QToolBar>
#include <QUndoStack>
#include <QUrl>
#include <QVBoxLayout>
#include <algorithm>

#include "archet/analysis/playability.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/ui/appearance.hpp"
#include "archet/ui/compare_view.hpp"
#include "archet/ui/elided_label.hpp"
#include "archet/ui/gesture_pad.hpp"
#include "archet/ui/graph_view.hpp"
#include "archet/ui/help_texts.hpp"
#include "archet/ui/inspector.hpp"
#include "archet/ui/library_panel.hpp"
#include "archet/ui/model_document.hpp"
#include "archet/ui/modes_panel.hpp"
#include "archet/ui/new_string_dialog.hpp"
#include "archet/ui/playability_panel.hpp"
#include "archet/ui/recording_clock.hpp"
#include "archet/ui/scope_panel.hpp"
#include "archet/ui/settings_dialog.hpp"
#include "archet/ui/sound_examples_dialog.hpp"
#include "archet/ui/studio_settings.hpp"
#include "archet/ui/takes_panel.hpp"
#include "archet/ui/widget_export.hpp"

namespace archet::ui {

namespace {
constexpr int kDisplayMs = 33;          // scopes at 30 frames a second
constexpr int kAutosaveDelayMs = 2000;  // after the newest edit
constexpr int kRecentFiles = 8;

// What the pad can play on this model, when it cannot: said on the pad, not left silent.
QString unplayable_reason(const Model& model) {
    const bool hand = std::any_of(model.mats.begin(), model.mats.end(),
                                  [](const Mat& m) { return m.kind == MatKind::Gesture; });
    const bool bow = std::any_of(model.lias.begin(), model.lias.end(),
                                 [](const Lia& l) { return l.kind == LiaKind::BowFriction; });
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
    left->setObjectName("graph-scopes");
    left->addWidget(graph_);
    left->addWidget(scopes_);
    left->setStretchFactor(0, 1);
    left->setStretchFactor(1, 3);
    tabs_ = new QTabWidget;
    // In scroll areas: what a tab shows (a long inspector, a long message) never widens the
    // side column, resizes the window or moves the pad under the cursor.
    auto scrolled = [](QWidget* page) {
        auto* area = new QScrollArea;
        area->setWidget(page);
        area->setWidgetResizable(true);
        area->setFrameShape(QFrame::NoFrame);
        area->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
        return area;
    };
    tabs_->addTab(scrolled(inspector_), tr("Inspector"));
    tabs_->addTab(modes_, tr("Modes"));
    tabs_->addTab(takes_, tr("Takes"));
    tabs_->addTab(library_, tr("Library"));
    auto* side = new QWidget;
    auto* side_layout = new QVBoxLayout(side);
    side_layout->addWidget(
        new QLabel(tr("<b>Gesture pad</b> — drag across to bow, down to press")));
    side_layout->addWidget(pad_, 2);
    side_layout->addWidget(tabs_, 3);
    auto* split = new QSplitter;
    split->setObjectName("main-side");
    split->addWidget(left);
    split->addWidget(side);
    split->setStretchFactor(0, 3);
    split->setStretchFactor(1, 1);
    setCentralWidget(split);
    splitters_ = {left, split};

    engine_state_ = new QLabel;
    device_ = new ElidedLabel;
    meters_ = new QLabel;
    statusBar()->addPermanentWidget(engine_state_);
    statusBar()->addPermanentWidget(device_, 1);
    statusBar()->addPermanentWidget(meters_);
    build_menus();
    addToolBar(Qt::LeftToolBarArea, build_palette());

    set_documents_folder(QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation) +
                         "/Archet");
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
    // Edits are checked at the rate the engine's device runs the model at.
    connect(engine_, &EngineClient::status_changed, this,
            [this] { document_->set_running_rate(engine_->status().sample_rate); });
    connect(engine_, &EngineClient::message, this, [this](const QString& text) {
        // A take that clipped or was cut short stays said: longer in the status bar, and in
        // the Takes tab until the next take's news.
        const bool take = text.startsWith("take ");
        const bool warning = text.contains("clipped") || text.contains("interrupted");
        statusBar()->showMessage(text, take && warning ? 30000 : 8000);
        if (text.startsWith("take written")) takes_->refresh();
        if (take) takes_->show_note(text);
    });
    connect(engine_, &EngineClient::engine_lost, this,
            [this](const QString& why) { statusBar()->showMessage(why, 10000); });
    connect(&display_, &QTimer::timeout, this, &MainWindow::refresh);
    connect(&autosave_timer_, &QTimer::timeout, this, [this] {
        if (document_->modified()) autosave();
    });
    // The newest edit is autosaved a moment after it is made, not up to 30 s later.
    autosave_timer_.setSingleShot(true);
    // (During the signal the undo stack has not yet counted the edit: the timer checks later.)
    connect(document_, &ModelDocument::changed, this,
            [this] { autosave_timer_.start(kAutosaveDelayMs); });
    recording_clock_ = new RecordingClock;
    statusBar()->insertPermanentWidget(0, recording_clock_);
    engine_->start();
    display_.start(kDisplayMs);
    resize(1400, 900);
    restore_layout();
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
    action(file, tr("Save &as…"), QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_S),
           &MainWindow::save_as);
    file->addSeparator();
    action(file, tr("Render sound &examples…"), QKeySequence(), [this] {
        auto* dialog =
            new SoundExamplesDialog(resources_folder_, documents_folder_ + "/sound-examples", this);
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

    QMenu* appearance = view->addMenu(tr("&Appearance"));
    auto* appearances = new QActionGroup(appearance);
    for (const auto& [text, choice] :
         {std::pair{tr("Follow the &desktop"), Appearance::Desktop},
          std::pair{tr("&Light"), Appearance::Light}, std::pair{tr("Dar&k"), Appearance::Dark}}) {
        QAction* a = appearance->addAction(text);
        a->setCheckable(true);
        a->setChecked(saved_appearance() == choice);
        appearances->addAction(a);
        connect(a, &QAction::triggered, this, [choice] {
            apply_appearance(choice);
            save_appearance(choice);
        });
    }

    QMenu* play = menuBar()->addMenu(tr("&Play"));
    play_ = action(play, tr("&Play"), QKeySequence(Qt::Key_Space), &MainWindow::toggle_play);
    record_ = action(play, tr("&Record take"), QKeySequence(Qt::Key_R), &MainWindow::toggle_take);
    play->addSeparator();
    action(play, tr("Audio and &devices…"), QKeySequence(), [this] {
        SettingsDialog dialog(engine_->options(), this);
        if (dialog.exec() != QDialog::Accepted) return;
        engine_->reconfigure(dialog.options());
        save_engine_options(dialog.options());
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

    QMenu* help = menuBar()->addMenu(tr("&Help"));
    action(help, tr("&Keyboard shortcuts"), QKeySequence(Qt::Key_F1),
           [this] { QMessageBox::information(this, tr("Keyboard shortcuts"), shortcut_table()); });
    action(help, tr("&User guide"), QKeySequence(), [this] {
        const QString guide = user_guide_path();
        if (guide.isEmpty() || !QDesktopServices::openUrl(QUrl::fromLocalFile(guide)))
            statusBar()->showMessage(
                tr("The user guide is docs/user-guide.md in the source tree, or "
                   "/usr/share/doc/archet/user-guide.md once installed."),
                10000);
    });
    action(help, tr("&About Archet studio"), QKeySequence(),
           [this] { QMessageBox::about(this, tr("About Archet studio"), about_text()); });

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
    engine_->set_takes_folder(folder);  // the engine records only inside it
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

bool MainWindow::may_drop_edits() {
    if (!document_->modified()) return true;
    const auto answer = QMessageBox::question(
        this, tr("Unsaved changes"),
        tr("%1 has changes that are not saved. Save them first?")
            .arg(QString::fromStdString(document_->model().name)),
        QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, QMessageBox::Save);
    if (answer == QMessageBox::Cancel) return false;
    if (answer == QMessageBox::Save) {
        save();
        return !document_->modified();  // saving was cancelled or failed: keep the edits
    }
    return true;
}

bool MainWindow::is_template(const QString& path) const {
    if (path.isEmpty() || resources_folder_.isEmpty()) return false;
    const QString shipped = QFileInfo(resources_folder_).canonicalFilePath();
    const QString file = QFileInfo(path).canonicalFilePath();
    return !shipped.isEmpty() && file.startsWith(shipped + "/");
}

void MainWindow::set_documents_folder(const QString& folder) {
    documents_folder_ = folder;
    set_takes_folder(folder + "/takes");
}

bool MainWindow::open_file(const QString& path) {
    if (!may_drop_edits()) return false;
    try {
        Model model = load_model_file(path.toStdString());
        validate_model(model);
        open_model(model, path);
        remember_recent(path);
        save_last_model_path(QFileInfo(path).absoluteFilePath());
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
        save_last_model_path(QFileInfo(path).absoluteFilePath());
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
    if (!may_drop_edits()) return;
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

// A shipped model is a template: saving it writes a copy among the user's documents.
void MainWindow::save() {
    if (document_->path().isEmpty() || is_template(document_->path())) return save_as();
    save_to(document_->path());
}

void MainWindow::save_as() {
    QString suggested = document_->path();
    if (suggested.isEmpty() || is_template(suggested)) {
        QDir().mkpath(documents_folder() + "/models");
        const QString name = QString::fromStdString(document_->model().name);
        suggested =
            documents_folder() + "/models/" + (name.isEmpty() ? "untitled" : name) + ".json";
    }
    QString path = QFileDialog::getSaveFileName(this, tr("Save the model"), suggested,
                                                tr("Archet models (*.json)"));
    if (path.isEmpty()) return;
    if (!path.endsWith(".json")) path += ".json";
    if (is_template(path)) {
        QMessageBox::warning(this, tr("Cannot save"),
                             tr("%1 is a shipped model, kept as it came. Save your version "
                                "under another name or folder.")
                                 .arg(path));
        return;
    }
    save_to(path);
}

void MainWindow::closeEvent(QCloseEvent* e) {
    if (!may_drop_edits()) return e->ignore();
    save_layout();
    e->accept();
}

// Window geometry, splitters, the open tab and the graph's zoom, as the user left them.
void MainWindow::save_layout() {
    QSettings s;
    s.beginGroup("window");
    s.setValue("geometry", saveGeometry());
    s.setValue("state", saveState());
    for (QSplitter* splitter : splitters_)
        s.setValue("splitter/" + splitter->objectName(), splitter->saveState());
    s.setValue("tab", tabs_->currentIndex());
    if (graph_->fitting()) {  // nothing chosen: the next start fits the graph too
        s.remove("zoom");
    } else {
        s.setValue("zoom", graph_->zoom());
        s.setValue("zoom_model", QString::fromStdString(document_->model().name));
    }
}

void MainWindow::restore_layout() {
    QSettings s;
    s.beginGroup("window");
    if (s.contains("geometry")) restoreGeometry(s.value("geometry").toByteArray());
    if (s.contains("state")) restoreState(s.value("state").toByteArray());
    for (QSplitter* splitter : splitters_)
        if (s.contains("splitter/" + splitter->objectName()))
            splitter->restoreState(s.value("splitter/" + splitter->objectName()).toByteArray());
    tabs_->setCurrentIndex(s.value("tab", 0).toInt());
    saved_zoom_ = s.value("zoom", 0.0).toDouble();
    saved_zoom_model_ = s.value("zoom_model").toString();
}

void MainWindow::restore_zoom() {
    if (saved_zoom_ <= 0 || saved_zoom_model_ != QString::fromStdString(document_->model().name))
        return;
    graph_->zoom_to(saved_zoom_);
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
    scopes_->refresh(engine_->history(), engine_->shape(), rate);
    const ProbeHistory& h = engine_->history();
    pad_->set_feedback(h.latest(h.channel("hand_force_slide")),
                       h.latest(h.channel("hand_force_press")));
}

void MainWindow::show_status() {
    const EngineStatus& s = engine_->status();
    QString state = tr("engine: %1").arg(s.state);
    if (s.state == "running" && s.sample_rate > 0)
        state += tr(" at %1 kHz").arg(s.sample_rate / 1000, 0, 'g', 4);
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
