#pragma once
// The studio's main window: the model being played, its scopes, the gesture pad, transport
// and takes, with the engine's state in the status bar.

#include <QMainWindow>
#include <QString>
#include <QTimer>

#include "archet/model.hpp"
#include "archet/ui/engine_client.hpp"

class QAction;
class QLabel;

namespace archet::ui {

class GesturePad;
class ScopePanel;

class MainWindow : public QMainWindow {
    Q_OBJECT

  public:
    MainWindow(EngineClientOptions engine, QWidget* parent = nullptr);

    /// Plays `model` (its file, if any, for Save); errors go to a message box.
    void open_model(const Model& model, const QString& path = {});
    bool open_file(const QString& path);

    EngineClient& engine() { return *engine_; }
    GesturePad& pad() { return *pad_; }
    ScopePanel& scopes() { return *scopes_; }
    const Model& model() const { return model_; }
    /// Where takes go: a new folder per take under it.
    void set_takes_folder(const QString& folder) { takes_folder_ = folder; }

  private:
    void build_actions();
    void new_string();
    void open_dialog();
    void save_as();
    void toggle_play();
    void toggle_take();
    void refresh();
    void show_status();

    EngineClient* engine_;
    ScopePanel* scopes_;
    GesturePad* pad_;
    QLabel* summary_;
    QLabel* engine_state_;
    QLabel* device_;
    QLabel* meters_;
    QAction* play_;
    QAction* record_;
    QTimer display_;
    Model model_;
    std::vector<int> string_points_;  ///< which shape-frame entries are the string
    QString path_;
    QString takes_folder_;
    QString take_;  ///< the folder being recorded into
};

}  // namespace archet::ui
