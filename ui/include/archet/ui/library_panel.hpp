#pragma once
// The start page: the shipped models (the paper's strings at 110–880 Hz, homogeneous and
// harmonic) and the models opened lately; double-click one to open it.

#include <QWidget>

class QListWidget;

namespace archet::ui {

class LibraryPanel : public QWidget {
    Q_OBJECT

  public:
    explicit LibraryPanel(QWidget* parent = nullptr);
    /// Lists the models in `folder` (resources/models), `recent`, and the autosaves in
    /// `autosaves` (a folder), newest first, to recover work after a crash.
    void fill(const QString& folder, const QStringList& recent, const QString& autosaves = {});
    int shipped_count() const;

  signals:
    void open_requested(const QString& path);
    void new_string_requested();

  private:
    QListWidget* shipped_;
    QListWidget* recent_;
};

}  // namespace archet::ui
