#include "archet/ui/appearance.hpp"

#include <QApplication>
#include <QPalette>
#include <QProcess>
#include <QSettings>
#include <QStandardPaths>
#include <QStyle>
#include <QStyleFactory>

#include "archet/ui/plot_palette.hpp"

namespace archet::ui {

namespace {

QPalette dark_palette() {
    QPalette p;
    const QColor window(45, 45, 48), base(30, 30, 32), text(230, 230, 230), mid(110, 110, 115);
    p.setColor(QPalette::Window, window);
    p.setColor(QPalette::WindowText, text);
    p.setColor(QPalette::Base, base);
    p.setColor(QPalette::AlternateBase, window);
    p.setColor(QPalette::ToolTipBase, window);
    p.setColor(QPalette::ToolTipText, text);
    p.setColor(QPalette::Text, text);
    p.setColor(QPalette::Button, window);
    p.setColor(QPalette::ButtonText, text);
    p.setColor(QPalette::BrightText, QColor(255, 80, 80));
    p.setColor(QPalette::Mid, mid);
    p.setColor(QPalette::Dark, QColor(25, 25, 27));
    p.setColor(QPalette::Light, QColor(70, 70, 75));
    p.setColor(QPalette::Highlight, QColor(60, 120, 210));
    p.setColor(QPalette::HighlightedText, Qt::white);
    p.setColor(QPalette::Link, QColor(110, 170, 255));
    p.setColor(QPalette::PlaceholderText, QColor(150, 150, 150));
    for (auto role : {QPalette::WindowText, QPalette::Text, QPalette::ButtonText})
        p.setColor(QPalette::Disabled, role, QColor(130, 130, 130));
    return p;
}

// The palette and style Qt had before any was forced: the desktop's own.
struct Desktop {
    QPalette palette = QApplication::palette();
    QString style = QApplication::style()->name();
};
const Desktop& desktop() {
    static const Desktop original;
    return original;
}

}  // namespace

bool desktop_prefers_dark() {
    if (qEnvironmentVariable("GTK_THEME").endsWith(":dark")) return true;
    if (QStandardPaths::findExecutable("gsettings").isEmpty()) return false;
    QProcess gsettings;
    gsettings.start("gsettings", {"get", "org.gnome.desktop.interface", "color-scheme"});
    if (!gsettings.waitForFinished(500)) {
        gsettings.kill();
        return false;
    }
    return gsettings.readAllStandardOutput().contains("prefer-dark");
}

void apply_appearance(Appearance appearance) {
    const Desktop& own = desktop();
    const bool dark =
        appearance == Appearance::Dark ||
        (appearance == Appearance::Desktop && !is_dark(own.palette) && desktop_prefers_dark());
    if (appearance == Appearance::Desktop && !dark) {
        if (QApplication::style()->name() != own.style)
            QApplication::setStyle(QStyleFactory::create(own.style));
        QApplication::setPalette(own.palette);
        return;
    }
    // Fusion draws every widget from the palette, so both palettes look as meant.
    if (QStyle* fusion = QStyleFactory::create("Fusion")) QApplication::setStyle(fusion);
    QApplication::setPalette(dark ? dark_palette() : QApplication::style()->standardPalette());
}

Appearance saved_appearance() {
    const QString name = QSettings().value("appearance", "desktop").toString();
    return name == "dark"    ? Appearance::Dark
           : name == "light" ? Appearance::Light
                             : Appearance::Desktop;
}

void save_appearance(Appearance appearance) {
    QSettings().setValue("appearance", appearance == Appearance::Dark    ? "dark"
                                       : appearance == Appearance::Light ? "light"
                                                                         : "desktop");
}

}  // namespace archet::ui
