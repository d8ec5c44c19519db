#pragma once
// The studio's main window: the graph editor over the scopes, the gesture pad, the inspector
// and the modes beside them, menus for files, editing and playing, and the engine's state in
// the status bar. Every edit goes through the ModelDocument (undoable) and reaches the
// running engine: a parameter glides in, a new element reloads the model.

#include <QMainWindow>
#include <QString>
#include <QTimer>

#include "archet/model.hpp"
#include "archet/ui/engine_client.hpp"

class QAction;
class QLabel;
class QMenu;

namespace archet::ui {

class GesturePad;
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

    EngineClient& engine() { return *engine_; }
    ModelDocument& document() { return *document_; }
    GraphView& graph() { return *graph_; }
    Inspector& inspector() { return *inspector_; }
    ModesPanel& modes() { return *modes_; }
    GesturePad& pad() { return *pad_; }
    ScopePanel& scopes() { return *scopes_; }
    TakesPanel& takes() { return *takes_; }
    LibraryPanel& library() { return *library_; }
    /// Where the shipped models and gestures are (resources/).
    void set_resources_folder(const QString& folder);
    /// Where takes go (a new dated folder per take) and where autosaves go.
    void set_takes_folder(const QString& folder);
    void set_autosave_folder(const QString& folder) { autosave_folder_ = folder; }
    /// Writes the autosave now (the timer does it every 30 s when there are changes).
    QString autosave();

  protected:
    void closeEvent(QCloseEvent*) override;

  private:
    void build_menus();
    QToolBar* build_palette();
    void new_string();
    void open_dialog();
    void save();
    void save_as();
    void toggle_play();
    void toggle_take();
    void copy();
    void paste();
    void model_changed(int change, const QString& element, const QString& parameter);
    void refresh();
    void show_status();
    void remember_recent(const QString& path);
    void fill_recent_menu();
    void update_title();

    EngineClient* engine_;
    ModelDocument* document_;
    GraphView* graph_;
    Inspector* inspector_;
    ModesPanel* modes_;
    ScopePanel* scopes_;
    GesturePad* pad_;
    TakesPanel* takes_;
    LibraryPanel* library_;
    QLabel* engine_state_;
    QLabel* device_;
    QLabel* meters_;
    QAction* play_;
    QAction* record_;
    QMenu* recent_;
    QTimer display_;
    QTimer autosave_timer_;
    std::vector<int> string_points_;  ///< which shape-frame entries are the string
    QString takes_folder_;
    QString resources_folder_;
    QString autosave_folder_;
    QString take_;  ///< the folder being recorded into
};

}  // namespace archet::ui
