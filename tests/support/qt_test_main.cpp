// main() of the studio's test suites: a QApplication on Qt's offscreen platform, with
// QStandardPaths in test mode so that settings, takes and autosaves stay out of $HOME.

#include <gtest/gtest.h>

#include <QApplication>
#include <QSettings>
#include <QStandardPaths>

int main(int argc, char** argv) {
    qputenv("QT_QPA_PLATFORM", "offscreen");
    QStandardPaths::setTestModeEnabled(true);
    QApplication app(argc, argv);
    QSettings().clear();  // each run starts as a first start: no layout or model from the last
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
