#include "archet/ui/main_window.hpp"

#include <QAction>
#include <QActionGroup>
#include <QDesktopServices>
#include <QFileDialog>
#include <QMenuBar>
#include <QMessageBox>
#include <QStatusBar>
#include <QToolBar>
#include <QUndoStack>
#include <QUrl>
#include <optional>

#include "archet/analysis/playability.hpp"
#include "archet/midi/midi_mapping.hpp"
#include "archet/ui/appearance.hpp"
#include "archet/ui/bowing_maps_window.hpp"
#include "archet/ui/compare_view.hpp"
#include "archet/ui/gesture_pad.hpp"
#include "archet/ui/graph_view.hpp"
#include "archet/ui/help_texts.hpp"
#include "archet/ui/midi_learn_dialog.hpp"
#include "archet/ui/model_document.hpp"
#include "archet/ui/scope_panel.hpp"
#include "archet/ui/settings_dialog.hpp"
#include "archet/ui/sound_examples_dialog.hpp"
#include "archet/ui/studio_settings.hpp"
#include "archet/ui/widget_export.hpp"

// The main window's menus, its transport and palette tool bars, and the dialogs they open.

namespace archet::ui {

namespace {
// A dialog of its own, deleted when the user closes it; the window goes on.
void show_owned(QWidget* dialog) {
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    dialog->show();
}
}  // namespace

template <typename Slot>
QAction* MainWindow::add_action(QMenu* menu, const QString& text, QKeySequence keys, Slot slot) {
    QAction* a = menu->addAction(text);
    a->setShortcut(keys);
    connect(a, &QAction::triggered, this, slot);
    return a;
}

void MainWindow::build_menus() {
    build_file_menu();
    const auto [undo, redo] = build_edit_menu();
    build_view_menu();
    build_play_menu();
    build_help_menu();
    auto* bar = addToolBar(tr("Transport"));
    bar->setObjectName("transport");
    bar->addAction(play_);
    bar->addAction(record_);
    bar->addSeparator();
    bar->addAction(undo);
    bar->addAction(redo);
}

void MainWindow::build_file_menu() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    add_action(file, tr("&New bowed string…"), QKeySequence::New, &MainWindow::new_string);
    add_action(file, tr("&Open…"), QKeySequence::Open, &MainWindow::open_dialog);
    recent_ = file->addMenu(tr("Open &recent"));
    fill_recent_menu();
    add_action(file, tr("&Save"), QKeySequence::Save, &MainWindow::save);
    add_action(file, tr("Save &as…"), QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_S),
               &MainWindow::save_as);
    file->addSeparator();
    add_action(file, tr("Render sound &examples…"), QKeySequence(), [this] {
        show_owned(new SoundExamplesDialog(resources_folder_, documents_folder_ + "/sound-examples",
                                           this));
    });
    file->addSeparator();
    add_action(file, tr("&Quit"), QKeySequence::Quit, &QWidget::close);
}

std::pair<QAction*, QAction*> MainWindow::build_edit_menu() {
    QMenu* edit = menuBar()->addMenu(tr("&Edit"));
    QAction* undo = document_->undo_stack().createUndoAction(this, tr("&Undo"));
    undo->setShortcut(QKeySequence::Undo);
    QAction* redo = document_->undo_stack().createRedoAction(this, tr("&Redo"));
    redo->setShortcut(QKeySequence::Redo);
    edit->addAction(undo);
    edit->addAction(redo);
    edit->addSeparator();
    add_action(edit, tr("&Copy"), QKeySequence::Copy, &MainWindow::copy);
    add_action(edit, tr("&Paste"), QKeySequence::Paste, &MainWindow::paste);
    add_action(edit, tr("&Delete"), QKeySequence::Delete, [this] {
        if (!graph_->selected_ids().isEmpty()) document_->remove(graph_->selected_ids());
    });
    return {undo, redo};
}

void MainWindow::build_view_menu() {
    QMenu* view = menuBar()->addMenu(tr("&View"));
    add_action(view, tr("&Fit the graph"), QKeySequence(Qt::CTRL | Qt::Key_0),
               [this] { graph_->fit(); });
    // Ctrl+= as well as Ctrl++: on most keyboards + needs Shift.
    add_action(view, tr("Zoom &in"), QKeySequence::ZoomIn, [this] {
        graph_->zoom_in();
    })->setShortcuts({QKeySequence::ZoomIn, QKeySequence(Qt::CTRL | Qt::Key_Equal)});
    add_action(view, tr("Zoom &out"), QKeySequence::ZoomOut, [this] { graph_->zoom_out(); });
    add_action(view, tr("F&reeze scopes"), QKeySequence(Qt::Key_F),
               [this] { scopes_->set_frozen(!scopes_->frozen()); });
    add_action(view, tr("&Export scopes…"), QKeySequence(Qt::CTRL | Qt::Key_E), [this] {
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
}

void MainWindow::build_play_menu() {
    QMenu* play = menuBar()->addMenu(tr("&Play"));
    play_ = add_action(play, tr("&Play"), QKeySequence(Qt::Key_Space), &MainWindow::toggle_play);
    record_ =
        add_action(play, tr("&Record take"), QKeySequence(Qt::Key_R), &MainWindow::toggle_take);
    play->addSeparator();
    add_action(play, tr("Audio and &devices…"), QKeySequence(), &MainWindow::open_settings);
    add_action(play, tr("&MIDI learn…"), QKeySequence(), &MainWindow::open_midi_learn);
    add_action(play, tr("Playa&bility map…"), QKeySequence(Qt::CTRL | Qt::Key_M),
               [this] { open_bowing_maps(BowingMapsWindow::Tab::Playability); });
    add_action(play, tr("&Attack map…"), QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_M),
               [this] { open_bowing_maps(BowingMapsWindow::Tab::Attack); });
    add_action(play, tr("&Compare settings…"), QKeySequence(Qt::CTRL | Qt::Key_K),
               [this] { show_owned(new CompareView(document_->model(), this)); });
}

void MainWindow::build_help_menu() {
    QMenu* help = menuBar()->addMenu(tr("&Help"));
    add_action(help, tr("&Keyboard shortcuts"), QKeySequence(Qt::Key_F1), [this] {
        QMessageBox::information(this, tr("Keyboard shortcuts"), shortcut_table());
    });
    add_action(help, tr("&User guide"), QKeySequence(), [this] {
        const QString guide = user_guide_path();
        if (guide.isEmpty() || !QDesktopServices::openUrl(QUrl::fromLocalFile(guide)))
            statusBar()->showMessage(
                tr("The user guide is docs/user-guide.md in the source tree, or "
                   "/usr/share/doc/archet/user-guide.md once installed."),
                10000);
    });
    add_action(help, tr("&About Archet studio"), QKeySequence(),
               [this] { QMessageBox::about(this, tr("About Archet studio"), about_text()); });
}

void MainWindow::open_settings() {
    SettingsDialog dialog(engine_->options(), this);
    if (dialog.exec() != QDialog::Accepted) return;
    engine_->reconfigure(dialog.options());
    save_engine_options(dialog.options());
}

// The mapping the engine plays MIDI with, edited by moving the controllers; once saved, the
// engine restarts with it (the model and what plays carry over).
void MainWindow::open_midi_learn() {
    EngineClientOptions options = engine_->options();
    if (options.midi.isEmpty()) {
        statusBar()->showMessage(
            tr("MIDI input is off: choose a MIDI input in Play → Audio and devices first"), 10000);
        return;
    }
    midi::MidiMapping mapping = midi::default_midi_mapping();
    if (!options.midi_map.isEmpty()) {
        try {
            mapping = midi::load_midi_mapping(options.midi_map.toStdString());
        } catch (const std::exception& e) {
            statusBar()->showMessage(
                tr("%1; starting from STK's Bowed's map").arg(QString::fromUtf8(e.what())), 10000);
        }
    }
    auto* dialog = new MidiLearnDialog(mapping, document_->model(), this);
    connect(engine_, &EngineClient::midi_controller, dialog, &MidiLearnDialog::heard);
    connect(dialog, &QDialog::accepted, this, [this, dialog] {
        EngineClientOptions o = engine_->options();
        o.midi_map = dialog->saved_path();
        engine_->reconfigure(o);
        save_engine_options(o);
        statusBar()->showMessage(tr("MIDI plays with %1 now").arg(o.midi_map), 5000);
    });
    show_owned(dialog);
}

// One window for both maps, kept once made: a map computed stays there for the next look, and
// the window follows the open model (the next Compute maps it as it is then).
void MainWindow::open_bowing_maps(BowingMapsWindow::Tab tab) {
    if (maps_) return maps_->show_tab(tab);
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
    maps_ = new BowingMapsWindow(document_->model(), here, this);
    // Moving an element on the canvas changes no physics.
    connect(document_, &ModelDocument::changed, maps_, [this](ModelDocument::Change change) {
        if (change != ModelDocument::Change::Layout) maps_->set_model(document_->model());
    });
    connect(document_, &ModelDocument::replaced, maps_,
            [this] { maps_->set_model(document_->model()); });
    maps_->show_tab(tab);
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
    tool(tr("Select"),
         tr("Select, drag to move, drag the background to pan, Shift+drag for several (Esc)"),
         [this] { graph_->set_tool(Tool::Select); })
        ->setChecked(true);
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

}  // namespace archet::ui
