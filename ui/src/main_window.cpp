#include "archet/ui/main_window.hpp"

#include <QApplication>
#include <QClipboard>
#include <QCloseEvent>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QScrollArea>
#include <QSettings>
#include <QSplitter>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTabWidget>
#include <QToolBar>
#include <QUndoStack>
#include <QVBoxLayout>

#include "archet/ui/elided_label.hpp"
#include "archet/ui/gesture_pad.hpp"
#include "archet/ui/graph_view.hpp"
#include "archet/ui/inspector.hpp"
#include "archet/ui/library_panel.hpp"
#include "archet/ui/model_document.hpp"
#include "archet/ui/modes_panel.hpp"
#include "archet/ui/recording_clock.hpp"
#include "archet/ui/scope_panel.hpp"
#include "archet/ui/stroke_driver.hpp"
#include "archet/ui/sweep_form.hpp"
#include "archet/ui/takes_panel.hpp"

// The window's parts, a file each: this one builds the window and keeps its layout;
// main_window_menus.cpp the menus, palette and dialogs; main_window_files.cpp opening, saving
// and autosaving; main_window_engine.cpp the live engine (play, takes, the status bar).

namespace archet::ui {

namespace {
constexpr int kDisplayMs = 33;  // scopes at 30 frames a second
}  // namespace

MainWindow::MainWindow(EngineClientOptions options, QWidget* parent) : QMainWindow(parent) {
    engine_ = new EngineClient(std::move(options), this);
    document_ = new ModelDocument(this);
    build_panels();
    build_status_bar();
    build_menus();
    addToolBar(Qt::LeftToolBarArea, build_palette());
    set_documents_folder(QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation) +
                         "/Archet");
    autosave_folder_ =
        QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + "/autosave";
    connect_panels();
    connect_engine();
    connect_autosave();
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

// The graph over the scopes; beside them the gesture pad over the tabs.
void MainWindow::build_panels() {
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
    auto* side = new QWidget;
    auto* side_layout = new QVBoxLayout(side);
    side_layout->addWidget(
        new QLabel(tr("<b>Gesture pad</b> — drag across to bow, down to press")));
    side_layout->addWidget(pad_, 2);
    side_layout->addLayout(build_stroke_row());
    side_layout->addWidget(build_tabs(), 3);
    auto* split = new QSplitter;
    split->setObjectName("main-side");
    split->addWidget(left);
    split->addWidget(side);
    split->setStretchFactor(0, 3);
    split->setStretchFactor(1, 1);
    setCentralWidget(split);
    splitters_ = {left, split};
}

// A stroke from rest at a chosen acceleration, as the attack map plays them.
QHBoxLayout* MainWindow::build_stroke_row() {
    stroke_ = new StrokeDriver(*pad_, this);
    auto* acceleration = number_box(0.1, 100, 8, 1, tr(" m/s²"));
    acceleration->setObjectName("stroke-acceleration");
    auto* button = new QPushButton(tr("Stroke"));
    button->setObjectName("stroke");
    button->setToolTip(
        tr("Slides the bow from where it is, from rest, with this acceleration of the pad's "
           "slide axis, at the pad's press (press first: the wheel, or Shift as you let go)"));
    connect(button, &QPushButton::clicked, this, [this, acceleration] {
        stroke_->running() ? stroke_->stop() : stroke_->start(acceleration->value());
    });
    connect(stroke_, &StrokeDriver::finished, button, [button] { button->setText(tr("Stroke")); });
    connect(button, &QPushButton::clicked, this,
            [this, button] { button->setText(stroke_->running() ? tr("Stop") : tr("Stroke")); });
    auto* row = new QHBoxLayout;
    row->addWidget(new QLabel(tr("From rest at")));
    row->addWidget(acceleration);
    row->addWidget(button);
    row->addStretch();
    return row;
}

QTabWidget* MainWindow::build_tabs() {
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
    return tabs_;
}

void MainWindow::build_status_bar() {
    recording_clock_ = new RecordingClock;
    engine_state_ = new QLabel;
    device_ = new ElidedLabel;
    meters_ = new QLabel;
    statusBar()->addPermanentWidget(recording_clock_);
    statusBar()->addPermanentWidget(engine_state_);
    statusBar()->addPermanentWidget(device_, 1);
    statusBar()->addPermanentWidget(meters_);
}

// The panels talk to each other and to the document; the engine's side is connect_engine().
void MainWindow::connect_panels() {
    connect(library_, &LibraryPanel::open_requested, this,
            [this](const QString& p) { open_file(p); });
    connect(library_, &LibraryPanel::new_string_requested, this, &MainWindow::new_string);
    connect(graph_, &GraphView::selection_changed, this, [this](const QStringList& ids) {
        inspector_->show_element(ids.size() == 1 ? ids.front() : QString());
    });
    connect(document_, &ModelDocument::path_changed, this, [this] { update_title(); });
    connect(&document_->undo_stack(), &QUndoStack::cleanChanged, this, [this] { update_title(); });
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

void MainWindow::update_title() {
    const QString name = QString::fromStdString(document_->model().name);
    setWindowTitle(tr("%1%2 — Archet studio")
                       .arg(name.isEmpty() ? tr("untitled") : name,
                            document_->modified() ? QStringLiteral(" *") : QString()));
}

}  // namespace archet::ui
