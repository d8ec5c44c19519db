#include "archet/ui/help_texts.hpp"

#include <QApplication>
#include <QFileInfo>
#include <QObject>
#include <utility>

namespace archet::ui {

QString shortcut_table() {
    const std::pair<const char*, const char*> rows[] = {
        {"Space", "play / stop"},
        {"R", "record a take / stop recording"},
        {"F", "freeze the scopes"},
        {"Ctrl+E", "export the scopes (PNG, PDF)"},
        {"Ctrl+M", "playability map"},
        {"Ctrl+K", "compare settings"},
        {"Ctrl+N", "new bowed string"},
        {"Ctrl+O", "open a model"},
        {"Ctrl+S", "save (a shipped model: save a copy in your documents)"},
        {"Ctrl+Shift+S", "save as"},
        {"Ctrl+Z / Ctrl+Shift+Z", "undo / redo"},
        {"Ctrl+C / Ctrl+V", "copy / paste elements"},
        {"Delete", "delete the selected elements"},
        {"Ctrl+0", "fit the graph"},
        {"Pad: drag", "bow across, press down; let go lifts the bow, Shift keeps it"},
        {"F1", "this table"}};
    QString html = "<table cellspacing=6>";
    for (const auto& [keys, what] : rows)
        html += QString("<tr><td><b>%1</b></td><td>%2</td></tr>")
                    .arg(QString(keys).toHtmlEscaped(), QObject::tr(what).toHtmlEscaped());
    return html + "</table>";
}

QString about_text() {
    return QObject::tr(
               "<h3>Archet studio %1</h3>"
               "<p>Physically modelled bowed strings in the CORDIS-ANIMA mass-interaction "
               "formalism, played live through a force-feedback gesture.</p>"
               "<p>Built with Qt %2 (LGPL-3.0), QCustomPlot (GPL-3.0), Eigen (MPL-2.0), "
               "RtAudio (MIT-style), libsndfile (LGPL-2.1), nlohmann-json (MIT), CLI11 "
               "(BSD-3-Clause), SDL2 (zlib), libevdev (MIT) and JACK (LGPL-2.1).</p>")
        .arg(QApplication::applicationVersion().isEmpty() ? QStringLiteral(ARCHET_VERSION)
                                                          : QApplication::applicationVersion(),
             qVersion());
}

QString user_guide_path() {
    const QString beside = QApplication::applicationDirPath();
    for (const QString& candidate :
         {QStringLiteral("/usr/share/doc/archet/user-guide.md"),
          beside + "/../../docs/user-guide.md", beside + "/../share/doc/archet/user-guide.md"})
        if (QFileInfo::exists(candidate)) return QFileInfo(candidate).canonicalFilePath();
    return {};
}

}  // namespace archet::ui
