// MIDI in the studio under Qt's offscreen platform: the settings offer MIDI off, the engine's own
// port on either API and every source listed, and refuse a mapping file the engine would refuse,
// saying why; MIDI learn assigns the controller the player moved to what they chose, with its
// range, refuses a range the parameter cannot take, and saves a file the engine reads back.

#include <gtest/gtest.h>

#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QTableWidget>
#include <fstream>

#include "archet/files/model_file.hpp"
#include "archet/midi/midi_mapping.hpp"
#include "archet/ui/midi_learn_dialog.hpp"
#include "archet/ui/settings_dialog.hpp"
#include "test_support.hpp"

namespace archet::ui {
namespace {

TEST(MidiSettings, OffByDefaultThenTheEnginesOwnPortOnEitherApi) {
    SettingsDialog dialog(EngineClientOptions{});
    auto* midi = dialog.findChild<QComboBox*>("midi");
    ASSERT_NE(midi, nullptr);
    EXPECT_EQ(dialog.options().midi, "") << "off until chosen";
    midi->setCurrentIndex(2);
    EXPECT_EQ(dialog.options().midi, "virtual");
    EXPECT_EQ(dialog.options().midi_api, "jack");
    EngineClientOptions gone;
    gone.midi = "Keystation 49", gone.midi_api = "alsa";
    SettingsDialog again(gone);
    EXPECT_EQ(again.options().midi, "Keystation 49") << "a source unplugged now stays chosen";
    EXPECT_TRUE(again.findChild<QComboBox*>("midi")->currentText().endsWith("(not found now)"));
    QDir().mkpath(ARCHET_ARTIFACT_DIR);
    EXPECT_TRUE(again.grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("studio-settings-midi.png")));
}

TEST(MidiSettings, AMappingFileTheEngineWouldRefuseIsRefusedHere) {
    const auto dir = test::temp_dir("midi-settings");
    std::ofstream(dir / "bad.json") << R"({"format": "archet-midi-map", "channel": 40})";
    SettingsDialog dialog(EngineClientOptions{});
    dialog.findChild<QLineEdit*>("midi_map")
        ->setText(QString::fromStdString((dir / "bad.json").string()));
    dialog.accept();
    EXPECT_NE(dialog.result(), QDialog::Accepted);
    auto* problem = dialog.findChild<QLabel*>("midi_map_problem");
    EXPECT_TRUE(problem->text().contains("channel")) << problem->text().toStdString();
    write_file_atomically(dir / "good.json",
                          midi::write_midi_mapping(midi::default_midi_mapping()));
    dialog.findChild<QLineEdit*>("midi_map")
        ->setText(QString::fromStdString((dir / "good.json").string()));
    dialog.accept();
    EXPECT_EQ(dialog.result(), QDialog::Accepted);
    EXPECT_EQ(dialog.options().midi_map.toStdString(), (dir / "good.json").string());
}

TEST(MidiLearn, TheControllerMovedIsAssignedWithItsRangeAndSavedForTheEngine) {
    const Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    MidiLearnDialog dialog(midi::default_midi_mapping(), model);
    auto* table = dialog.findChild<QTableWidget*>("routes");
    ASSERT_NE(table, nullptr);
    EXPECT_EQ(table->rowCount(), 5) << "STK's Bowed's five controllers";
    auto* target = dialog.findChild<QComboBox*>("target");
    const int mu = target->findText("friction.mu_s");
    ASSERT_GE(mu, 0) << "the bow's friction is offered";
    EXPECT_LT(target->findText("s12.mass"), 0) << "the string's own masses are not listed";
    target->setCurrentIndex(mu);
    dialog.heard(74, "CC 74 = 90 (channel 1)");
    EXPECT_TRUE(dialog.findChild<QLabel*>("heard")->text().contains("CC 74"));
    auto boxes = dialog.findChildren<QDoubleSpinBox*>();
    ASSERT_EQ(boxes.size(), 2);
    boxes[0]->setValue(0.5), boxes[1]->setValue(0.9);
    dialog.assign();
    ASSERT_EQ(table->rowCount(), 6);
    dialog.resize(560, 520);
    QDir().mkpath(ARCHET_ARTIFACT_DIR);
    EXPECT_TRUE(dialog.grab().save(QDir(ARCHET_ARTIFACT_DIR).filePath("studio-midi-learn.png")));
    const midi::ControlRoute* route = dialog.mapping().route(74);
    ASSERT_NE(route, nullptr);
    EXPECT_EQ(route->parameter.text(), "friction.mu_s");
    EXPECT_EQ(route->minimum, 0.5);
    EXPECT_EQ(route->maximum, 0.9);

    boxes[1]->setValue(50);  // beyond what mu_s may be
    dialog.assign();
    EXPECT_TRUE(dialog.findChild<QLabel*>("problem")->text().contains("friction.mu_s"));
    EXPECT_EQ(dialog.mapping().route(74)->maximum, 0.9) << "the refused range changed nothing";

    const auto dir = test::temp_dir("midi-learn");
    const QString path = QString::fromStdString((dir / "map.json").string());
    ASSERT_TRUE(dialog.save_to(path));
    const midi::MidiMapping read = midi::load_midi_mapping(path.toStdString());
    ASSERT_NE(read.route(74), nullptr);
    EXPECT_EQ(read.route(74)->parameter.text(), "friction.mu_s");
    EXPECT_EQ(dialog.saved_path(), path);
}

}  // namespace
}  // namespace archet::ui
