#include "archet/ui/sound_examples_dialog.hpp"

#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QVBoxLayout>

#include "archet/common/number_text.hpp"
#include "archet/sound_examples.hpp"

namespace archet::ui {

SoundExamplesDialog::SoundExamplesDialog(QString resources, QString folder, QWidget* parent)
    : QDialog(parent), resources_(std::move(resources)) {
    setWindowTitle(tr("Render sound examples"));
    folder_ = new QLineEdit(folder);
    auto* browse = new QPushButton(tr("Choose…"));
    list_ = new QListWidget;
    for (const SoundExample& e : sound_examples())
        list_->addItem(QString::fromStdString(e.file + " — " + e.what));
    progress_ = new QProgressBar;
    progress_->setRange(0, static_cast<int>(sound_examples().size()));
    progress_->setValue(0);
    message_ = new QLabel(tr("The shipped strings under the shipped gestures, rendered offline."));
    message_->setWordWrap(true);
    start_ = new QPushButton(tr("Render"));
    cancel_ = new QPushButton(tr("Cancel"));
    cancel_->setEnabled(false);
    auto* where = new QHBoxLayout;
    where->addWidget(new QLabel(tr("Folder")));
    where->addWidget(folder_, 1);
    where->addWidget(browse);
    auto* buttons = new QHBoxLayout;
    buttons->addWidget(start_);
    buttons->addWidget(cancel_);
    buttons->addWidget(progress_, 1);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(where);
    layout->addWidget(list_, 1);
    layout->addLayout(buttons);
    layout->addWidget(message_);
    connect(browse, &QPushButton::clicked, this, [this] {
        const QString dir =
            QFileDialog::getExistingDirectory(this, tr("Render into"), folder_->text());
        if (!dir.isEmpty()) folder_->setText(dir);
    });
    connect(start_, &QPushButton::clicked, this, &SoundExamplesDialog::start);
    connect(cancel_, &QPushButton::clicked, this, &SoundExamplesDialog::cancel);
    connect(&job_, &BackgroundJob::progressed, this, [this](std::size_t done) {
        rendered_ = static_cast<int>(done);
        progress_->setValue(rendered_);
    });
    resize(700, 420);
}

void SoundExamplesDialog::start() {
    if (busy()) return;
    rendered_ = 0;
    progress_->setValue(0);
    start_->setEnabled(false);
    cancel_->setEnabled(true);
    message_->setText(tr("rendering…"));
    const std::string resources = resources_.toStdString(), folder = folder_->text().toStdString();
    job_.start(
        [resources, folder](BackgroundJob::Control& control) {
            std::size_t count = 0;
            for (const SoundExample& e : sound_examples()) {
                if (control.cancelled()) return false;
                render_sound_example(e, resources, folder);
                control.progress(++count, sound_examples().size());
            }
            return true;
        },
        [this](bool all) { done(rendered_, all ? QString() : tr("cancelled")); },
        [this](const QString& error) { done(rendered_, error); });
}

void SoundExamplesDialog::done(int rendered, const QString& error) {
    rendered_ = rendered;
    start_->setEnabled(true);
    cancel_->setEnabled(false);
    message_->setText(
        error.isEmpty() ? tr("%1 written to %2")
                              .arg(QString::fromStdString(count_of(
                                       static_cast<std::size_t>(rendered), "example", "examples")),
                                   folder_->text())
                        : tr("%1 (%2 written)").arg(error).arg(rendered));
    emit finished_rendering(rendered, error);
}

}  // namespace archet::ui
