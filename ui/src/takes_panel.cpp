#include "archet/ui/takes_panel.hpp"

#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QVBoxLayout>
#include <cmath>

#include "archet/sound_file_reader.hpp"
#include "archet/sound_file_writer.hpp"

namespace archet::ui {

TakesPanel::TakesPanel(QWidget* parent) : QWidget(parent) {
    list_ = new QListWidget;
    message_ = new QLabel(tr("Record a take with R; it appears here."));
    message_->setWordWrap(true);
    auto* play = new QPushButton(tr("Play"));
    auto* stop = new QPushButton(tr("Stop"));
    auto* export_audio = new QPushButton(tr("Export…"));
    export_audio->setToolTip(tr("The take's audio as WAV or FLAC, or its probes as CSV"));
    auto* buttons = new QHBoxLayout;
    buttons->addWidget(play);
    buttons->addWidget(stop);
    buttons->addWidget(export_audio);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(list_, 1);
    layout->addLayout(buttons);
    layout->addWidget(message_);
    connect(play, &QPushButton::clicked, this, [this] { this->play(); });
    connect(stop, &QPushButton::clicked, this, [this] { player_.stop(); });
    connect(export_audio, &QPushButton::clicked, this, [this] {
        const QString path = QFileDialog::getSaveFileName(
            this, tr("Export the take"),
            list_->currentItem() ? list_->currentItem()->text() + ".wav" : "",
            tr("Audio (*.wav *.flac);;Probes (*.csv)"));
        if (!path.isEmpty()) export_to(path);
    });
}

void TakesPanel::set_folder(const QString& folder) {
    folder_ = folder;
    refresh();
}

void TakesPanel::refresh() {
    const QString current = list_->currentItem() ? list_->currentItem()->text() : QString();
    list_->clear();
    QDir dir(folder_);
    for (const QString& take :
         dir.entryList(QDir::Dirs | QDir::NoDotAndDotDot, QDir::Name | QDir::Reversed))
        if (QFile::exists(dir.filePath(take + "/take.wav"))) list_->addItem(take);
    if (!current.isEmpty()) select(current);
}

void TakesPanel::show_note(const QString& text) {
    message_->setText(text);
}

QString TakesPanel::note() const {
    return message_->text();
}

QStringList TakesPanel::takes() const {
    QStringList names;
    for (int i = 0; i < list_->count(); ++i) names << list_->item(i)->text();
    return names;
}

void TakesPanel::select(const QString& take) {
    const auto found = list_->findItems(take, Qt::MatchExactly);
    if (!found.isEmpty()) list_->setCurrentItem(found.front());
}

QString TakesPanel::selected_folder() const {
    return list_->currentItem() ? QDir(folder_).filePath(list_->currentItem()->text()) : QString();
}

bool TakesPanel::play() {
    const QString take = selected_folder();
    if (take.isEmpty()) return false;
    try {
        SoundData sound = read_sound_file((take + "/take.wav").toStdString());
        player_.play(sound.samples, sound.sample_rate);
        message_->setText(tr("playing on %1").arg(QString::fromStdString(player_.description())));
        return true;
    } catch (const std::exception& e) {
        message_->setText(QString::fromUtf8(e.what()));
        return false;
    }
}

bool TakesPanel::export_to(const QString& path) {
    const QString take = selected_folder();
    if (take.isEmpty()) return false;
    try {
        if (path.endsWith(".csv", Qt::CaseInsensitive)) {
            QFile::remove(path);
            if (!QFile::copy(take + "/probes.csv", path))
                throw std::runtime_error("cannot write " + path.toStdString());
        } else {
            const SoundData sound = read_sound_file((take + "/take.wav").toStdString());
            const SoundFormat format =
                path.endsWith(".flac", Qt::CaseInsensitive) ? SoundFormat::Flac : SoundFormat::Wav;
            SoundFileWriter writer(path.toStdString(), format,
                                   static_cast<int>(std::lround(sound.sample_rate)));
            writer.write(sound.samples.data(), sound.samples.size());
            writer.close();
        }
        message_->setText(tr("exported %1").arg(path));
        return true;
    } catch (const std::exception& e) {
        message_->setText(QString::fromUtf8(e.what()));
        return false;
    }
}

}  // namespace archet::ui
