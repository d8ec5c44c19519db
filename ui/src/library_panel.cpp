#include "archet/ui/library_panel.hpp"

#include <QDateTime>
#include <QDir>
#include <QFileInfo>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QVBoxLayout>

namespace archet::ui {

namespace {
constexpr int kPathRole = Qt::UserRole;
}

LibraryPanel::LibraryPanel(QWidget* parent) : QWidget(parent) {
    shipped_ = new QListWidget;
    recent_ = new QListWidget;
    auto* build = new QPushButton(tr("New bowed string…"));
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(build);
    layout->addWidget(new QLabel(tr("<b>Shipped strings</b> (double-click to open)")));
    layout->addWidget(shipped_, 2);
    layout->addWidget(new QLabel(tr("<b>Recent</b>")));
    layout->addWidget(recent_, 1);
    for (QListWidget* list : {shipped_, recent_})
        connect(list, &QListWidget::itemActivated, this, [this](QListWidgetItem* item) {
            emit open_requested(item->data(kPathRole).toString());
        });
    connect(build, &QPushButton::clicked, this, &LibraryPanel::new_string_requested);
}

void LibraryPanel::fill(const QString& folder, const QStringList& recent,
                        const QString& autosaves) {
    shipped_->clear();
    recent_->clear();
    const QDir dir(folder);
    for (const QString& name : dir.entryList({"*.json"}, QDir::Files, QDir::Name)) {
        auto* item = new QListWidgetItem(QFileInfo(name).completeBaseName(), shipped_);
        item->setData(kPathRole, dir.filePath(name));
    }
    for (const QString& path : recent) {
        auto* item = new QListWidgetItem(QFileInfo(path).fileName(), recent_);
        item->setData(kPathRole, path);
        item->setToolTip(path);
    }
    if (autosaves.isEmpty()) return;
    const QDir saved(autosaves);
    for (const QFileInfo& file : saved.entryInfoList({"*.json"}, QDir::Files, QDir::Time)) {
        auto* item = new QListWidgetItem(
            tr("%1 (autosaved %2)")
                .arg(file.completeBaseName(), file.lastModified().toString("yyyy-MM-dd hh:mm")),
            recent_);
        item->setData(kPathRole, file.absoluteFilePath());
        item->setToolTip(file.absoluteFilePath());
    }
}

int LibraryPanel::shipped_count() const {
    return shipped_->count();
}

}  // namespace archet::ui
