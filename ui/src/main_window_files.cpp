#include "archet/ui/main_window.hpp"

#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QMenu>
#include <QMessageBox>
#include <QProgressDialog>
#include <QSettings>
#include <QStatusBar>

#include "archet/builders/bowed_string.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/model_validation.hpp"
#include "archet/ui/graph_view.hpp"
#include "archet/ui/library_panel.hpp"
#include "archet/ui/model_document.hpp"
#include "archet/ui/new_string_dialog.hpp"
#include "archet/ui/studio_settings.hpp"
#include "archet/ui/takes_panel.hpp"

// The main window's files: models opened, saved (a shipped one as a copy) and autosaved, the
// recent list, and the folders takes and copies go to.

namespace archet::ui {

namespace {
constexpr int kAutosaveDelayMs = 2000;  // after the newest edit
constexpr int kRecentFiles = 8;
}  // namespace

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

void MainWindow::set_documents_folder(const QString& folder) {
    documents_folder_ = folder;
    set_takes_folder(folder + "/takes");
}

bool MainWindow::is_template(const QString& path) const {
    if (path.isEmpty() || resources_folder_.isEmpty()) return false;
    const QString shipped = QFileInfo(resources_folder_).canonicalFilePath();
    const QString file = QFileInfo(path).canonicalFilePath();
    return !shipped.isEmpty() && file.startsWith(shipped + "/");
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

void MainWindow::open_dialog() {
    const QString path =
        QFileDialog::getOpenFileName(this, tr("Open a model"), QFileInfo(document_->path()).path(),
                                     tr("Archet models (*.json)"));
    if (!path.isEmpty()) open_file(path);
}

void MainWindow::new_string() {
    if (!may_drop_edits()) return;
    NewStringDialog dialog(this);
    if (dialog.exec() == QDialog::Accepted) build_string(dialog.options());
}

// Tuning a long harmonic string solves eigenproblems of twice its size, and the band search
// plays 17 strokes: from under a second to about 15 s, while the engine and the pad go on.
bool MainWindow::build_string(const BowedStringOptions& options) {
    if (string_job_.busy()) return false;
    string_cancelled_ = false;
    string_progress_ = new QProgressDialog(
        tr("Building the string and finding its Helmholtz band…"), tr("Cancel"), 0, 0, this);
    string_progress_->setWindowTitle(tr("New bowed string"));
    string_progress_->setWindowModality(Qt::WindowModal);  // the model it replaces stays as is
    string_progress_->setMinimumDuration(0);
    connect(string_progress_, &QProgressDialog::canceled, this, &MainWindow::cancel_string);
    string_progress_->show();  // at once: it has no value to set that would show it later
    auto finish = [this] {
        string_progress_->deleteLater();
        string_progress_ = nullptr;
    };
    return string_job_.start(
        [options](BackgroundJob::Control& control) {
            return build_bowed_string(options, &control.cancel_flag());
        },
        [this, finish](const Model& model) {
            finish();
            open_model(model);
        },
        [this, finish](const QString& error) {
            finish();
            if (!string_cancelled_)
                QMessageBox::warning(this, tr("Cannot build that string"), error);
        });
}

void MainWindow::cancel_string() {
    string_cancelled_ = true;
    string_job_.cancel();
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

void MainWindow::connect_autosave() {
    connect(&autosave_timer_, &QTimer::timeout, this, [this] {
        if (document_->modified()) autosave();
    });
    // The newest edit is autosaved a moment after it is made, not up to 30 s later.
    autosave_timer_.setSingleShot(true);
    // (During the signal the undo stack has not yet counted the edit: the timer checks later.)
    connect(document_, &ModelDocument::changed, this,
            [this] { autosave_timer_.start(kAutosaveDelayMs); });
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
