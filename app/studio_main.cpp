// archet-studio: the Qt studio. `archet-studio [MODEL]` opens the model (by default the model
// file last opened or saved, else the shipped 220 Hz string) and plays it on a real-time
// engine process, with the audio settings of last time.

#include <QApplication>
#include <QCommandLineParser>
#include <QDir>
#include <QFileInfo>

#include "archet/builders/bowed_string.hpp"
#include "archet/ui/appearance.hpp"
#include "archet/ui/main_window.hpp"
#include "archet/ui/studio_settings.hpp"
#include "resource_folder.hpp"

int main(int argc, char** argv) {
    QApplication app(argc, argv);
    QApplication::setApplicationName("Archet studio");
    QApplication::setOrganizationName("Archet");
    QApplication::setApplicationVersion(ARCHET_VERSION);
    QCommandLineParser parser;
    parser.setApplicationDescription("Build, play and record bowed-string models");
    parser.addHelpOption();
    parser.addPositionalArgument("model", "Model file to open (.json)");
    QCommandLineOption audio("audio", "Audio output: auto, jack, pulse, alsa or null", "api",
                             "auto");
    parser.addOption(audio);
    parser.process(app);
    archet::ui::apply_appearance(archet::ui::saved_appearance());

    archet::ui::EngineClientOptions engine = archet::ui::restore_engine_options({});
    engine.archet_binary = QDir(QApplication::applicationDirPath()).filePath("archet");
    if (parser.isSet(audio)) engine.audio = parser.value(audio);
    archet::ui::MainWindow window(engine);
    const QString resources = QString::fromStdString(archet::cli::resource_folder().string());
    window.set_resources_folder(resources);
    const QStringList files = parser.positionalArguments();
    const QString shipped = resources + "/models/bowed-string-220.json";
    const QString last = archet::ui::last_model_path();
    if (!files.isEmpty()) {
        if (!window.open_file(files.front())) return 2;
    } else if (!last.isEmpty() && window.open_file(last)) {
        window.restore_zoom();
    } else if (QFileInfo::exists(shipped)) {
        window.open_file(shipped);
    } else {
        window.open_model(archet::build_bowed_string({}));
    }
    window.show();
    return QApplication::exec();
}
