#pragma once
// The studio's main window: the graph editor over the scopes, the gesture pad, the inspector
// and the modes beside them, menus for files, editing and playing, and the engine's state in
// the status bar. Every edit goes through the ModelDocument (undoable) and reaches the
// running engine: a parameter glides in, a new element reloads the model. Its parts are a
// source each: main_window.cpp (the window), _menus, _files and _engine.

#include <QElapsedTimer>
#include <QKeySequence>
#include <QMainWindow>
#include <QString>
#include <QTimer>
#include <utility>
#include <vector>

#include "archet/builders/bowed_string.hpp"
#include "archet/model/model.hpp"
#include "archet/ui/background_job.hpp"
#include "archet/ui/bowing_maps_window.hpp"
#include "archet/ui/engine_client.hpp"

class QAction;
class QHBoxLayout;
class QSplitter;
class QTabWidget;
class QLabel;
class QMenu;
class QProgressDialog;

namespace archet::ui {

class ElidedLabel;
class RecordingClock;
class GesturePad;
class StrokeDriver;
class GraphView;
class Inspector;
class LibraryPanel;
class TakesPanel;
class ModelDocument;
class ModesPanel;
class ScopePanel;

class MainWindow : public QMainWindow {
    Q_OBJECT

  public:
    MainWindow(EngineClientOptions engine, QWidget* parent = nullptr);
    ~MainWindow() override;

    /// Edits and plays `model` (its file, if any, for Save).
    void open_model(const Model& model, const QString& path = {});
    /// Errors go to a message box; returns whether the file was opened.
    bool open_file(const QString& path);
    bool save_to(const QString& path);
    /// Builds a new string off the GUI thread (tuning and the band search take seconds), with
    /// a progress dialog whose Cancel stops it, then opens it; the engine plays the model
    /// before it meanwhile. False while another build runs.
    bool build_string(const BowedStringOptions& options);
    bool building_string() const { return string_job_.busy(); }
    /// Stops the build; the model before it stays open.
    void cancel_string();

    EngineClient& engine() { return *engine_; }
    ModelDocument& document() { return *document_; }
    GraphView& graph() { return *graph_; }
    Inspector& inspector() { return *inspector_; }
    ModesPanel& modes() { return *modes_; }
    GesturePad& pad() { return *pad_; }
    /// Plays a stroke from rest at a chosen acceleration on the pad (the attack map's gesture).
    StrokeDriver& stroke() { return *stroke_; }
    ScopePanel& scopes() { return *scopes_; }
    TakesPanel& takes() { return *takes_; }
    LibraryPanel& library() { return *library_; }
    /// Where the shipped models and gestures are (resources/).
    void set_resources_folder(const QString& folder);
    /// Where takes go (a new dated folder per take) and where autosaves go.
    void set_takes_folder(const QString& folder);
    void set_autosave_folder(const QString& folder) { autosave_folder_ = folder; }
    /// Writes the autosave now (a timer does it 2 s after the newest edit).
    QString autosave();
    /// Asks before unsaved edits would be dropped (Save / Discard / Cancel); true to go on.
    bool may_drop_edits();
    /// A shipped model (under the resources folder): Save writes a copy elsewhere.
    bool is_template(const QString& path) const;
    /// Where Save As proposes a shipped model's copy (models/) and takes go (takes/): the
    /// user's documents, Archet/, unless set.
    const QString& documents_folder() const { return documents_folder_; }
    void set_documents_folder(const QString& folder);
    /// The zoom the graph had when the studio last closed, if it showed the same model.
    void restore_zoom();
    void save();
    void save_as();

  protected:
    void closeEvent(QCloseEvent*) override;

  private:
    // Building the window (main_window.cpp).
    void build_panels();
    QTabWidget* build_tabs();
    QHBoxLayout* build_stroke_row();
    void build_status_bar();
    void connect_panels();
    void save_layout();
    void restore_layout();
    void copy();
    void paste();
    void update_title();

    // Menus, tool bars and the dialogs they open (main_window_menus.cpp).
    template <typename Slot>
    QAction* add_action(QMenu* menu, const QString& text, QKeySequence keys, Slot slot);
    void build_menus();
    void build_file_menu();
    std::pair<QAction*, QAction*> build_edit_menu();  ///< undo and redo, for the tool bar
    void build_view_menu();
    void build_play_menu();
    void build_help_menu();
    QToolBar* build_palette();
    void open_settings();
    void open_midi_learn();
    /// The bowing maps window, brought up on `tab` (made the first time).
    void open_bowing_maps(BowingMapsWindow::Tab tab);

    // Files (main_window_files.cpp).
    void new_string();
    void open_dialog();
    void connect_autosave();
    void remember_recent(const QString& path);
    void fill_recent_menu();

    // The live engine (main_window_engine.cpp).
    void connect_engine();
    void toggle_play();
    void toggle_take();
    void model_changed(int change, const QString& element, const QString& name);
    /// The pad's keyboard row: the model's finger to `semitones` above the open string (−1:
    /// back to the open string), glided in like any parameter.
    void finger_to(int semitones);
    void refresh();
    void show_status();

    EngineClient* engine_;
    ModelDocument* document_;
    GraphView* graph_;
    Inspector* inspector_;
    ModesPanel* modes_;
    ScopePanel* scopes_;
    GesturePad* pad_;
    StrokeDriver* stroke_;
    TakesPanel* takes_;
    LibraryPanel* library_;
    QLabel* engine_state_;
    ElidedLabel* device_;
    QLabel* meters_;
    QAction* play_;
    QAction* record_;
    QMenu* recent_;
    QTimer display_;
    QTimer autosave_timer_;
    RecordingClock* recording_clock_;
    QTabWidget* tabs_;
    BowingMapsWindow* maps_ = nullptr;  ///< made when first asked for, then kept
    std::vector<QSplitter*> splitters_;
    double saved_zoom_ = 0;
    QString saved_zoom_model_;
    /// The document changed into a model that does not validate: the engine still plays an
    /// older one, so the next valid change reloads rather than glides.
    bool engine_behind_ = false;
    QString takes_folder_;
    QString resources_folder_;
    QString autosave_folder_;
    QString documents_folder_;
    QString take_;                                ///< the folder being recorded into
    QProgressDialog* string_progress_ = nullptr;  ///< while a new string builds
    bool string_cancelled_ = false;
    BackgroundJob string_job_;  ///< last: destroyed (cancelled and joined) first
};

}  // namespace archet::ui
