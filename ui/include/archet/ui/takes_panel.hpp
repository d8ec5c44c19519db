#pragma once
// The takes recorded so far (one folder each): play one back, export its audio as WAV or
// FLAC, or its probes as CSV.

#include <QWidget>

#include "archet/preview_player.hpp"

class QLabel;
class QListWidget;

namespace archet::ui {

class TakesPanel : public QWidget {
    Q_OBJECT

  public:
    explicit TakesPanel(QWidget* parent = nullptr);

    void set_folder(const QString& folder);
    void refresh();
    QStringList takes() const;
    void select(const QString& take);
    /// Plays the selected take; returns whether one played.
    bool play();
    /// Writes the selected take's audio to `path` (WAV or FLAC by suffix) or its probes (CSV).
    bool export_to(const QString& path);
    PreviewPlayer& player() { return player_; }
    /// Says something about the takes under the list (the engine's news of the last take:
    /// written, interrupted, clipped), until something else is said there.
    void show_note(const QString& text);
    QString note() const;

  private:
    QString selected_folder() const;

    QString folder_;
    QListWidget* list_;
    QLabel* message_;
    PreviewPlayer player_;  ///< the preview path, apart from the engine
};

}  // namespace archet::ui
