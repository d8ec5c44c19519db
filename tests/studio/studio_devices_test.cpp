// The studio's settings under Qt's offscreen platform: what may hold the bow is offered under
// the ids `--haptic` takes, from the list `archet devices` prints, and each one opens. A
// joystick is SDL's own virtual one (no hardware needed), as in the haptics suite.

#include <gtest/gtest.h>

#include <QComboBox>
#include <QSpinBox>

#include "archet/audio_output.hpp"
#include "archet/haptic_choice.hpp"
#include "archet/ui/settings_dialog.hpp"
#include "virtual_joystick.hpp"

namespace archet::ui {
namespace {

TEST(SettingsDevices, EveryHapticChoiceCarriesAnIdThatHapticOpens) {
    const test::VirtualJoystick stick;
    SettingsDialog dialog(EngineClientOptions{});
    auto* haptic = dialog.findChild<QComboBox*>("haptic");
    ASSERT_NE(haptic, nullptr);
    QStringList ids;
    for (int i = 0; i < haptic->count(); ++i) ids << haptic->itemData(i).toString();
    ASSERT_GE(ids.size(), 2);
    EXPECT_EQ(ids.mid(0, 2), (QStringList{"sim", "none"})) << "the pad's two ways first";
    for (int i = 0; i < haptic->count(); ++i) {
        haptic->setCurrentIndex(i);
        const std::string id = dialog.options().haptic.toStdString();
        EXPECT_EQ(id, ids[i].toStdString()) << "the options carry the chosen id";
        if (id.rfind("evdev:", 0) == 0) continue;  // a real joystick: not opened under test
        const HapticChoice opened = open_haptic_device(id);
        EXPECT_EQ(opened.device == nullptr, id == "none") << id;
    }
    if (!stick.ready()) GTEST_SKIP() << "SDL cannot attach a virtual joystick: " << SDL_GetError();
    const QString joystick = QString("sdl:%1").arg(stick.index());
    const int at = haptic->findData(joystick);
    ASSERT_GE(at, 0) << "the virtual joystick is offered: " << ids.join(", ").toStdString();
    EXPECT_TRUE(haptic->itemText(at).startsWith(QString("sdl %1: ").arg(stick.index())))
        << haptic->itemText(at).toStdString();
    EXPECT_TRUE(haptic->itemText(at).endsWith("(positions only)"));
}

// The OSC port: off by default, and what the dialog shows is what the engine is started with.
TEST(SettingsDevices, TheOscPortIsOffUntilChosen) {
    SettingsDialog dialog(EngineClientOptions{});
    auto* osc = dialog.findChild<QSpinBox*>("osc");
    ASSERT_NE(osc, nullptr);
    EXPECT_EQ(osc->text(), "off");
    EXPECT_EQ(dialog.options().osc_port, 0);
    osc->setValue(9000);
    EXPECT_EQ(dialog.options().osc_port, 9000);
}

TEST(SettingsDevices, TheChoicesAreTheOnesArchetDevicesLists) {
    SettingsDialog dialog(EngineClientOptions{});
    auto* haptic = dialog.findChild<QComboBox*>("haptic");
    ASSERT_NE(haptic, nullptr);
    QStringList offered;
    for (int i = 0; i < haptic->count(); ++i) offered << haptic->itemData(i).toString();
    QStringList listed{"none"};
    for (const HapticDeviceInfo& d : list_haptic_choices())
        listed << QString::fromStdString(d.id());
    offered.sort(), listed.sort();
    EXPECT_EQ(offered, listed);
}

// Audio: each API's default, then every output device `archet devices` lists, each carrying
// the --audio and --device the engine takes; a saved device that is gone falls back to its
// API's default.
TEST(SettingsDevices, EveryAudioChoiceCarriesTheApiAndDeviceTheEngineTakes) {
    SettingsDialog dialog(EngineClientOptions{});
    auto* audio = dialog.findChild<QComboBox*>("audio");
    ASSERT_NE(audio, nullptr);
    auto choice = [&](int i) {
        audio->setCurrentIndex(i);
        const EngineClientOptions o = dialog.options();
        return o.audio.toStdString() + " " + std::to_string(o.audio_device);
    };
    std::vector<std::string> offered;
    for (int i = 0; i < audio->count(); ++i) offered.push_back(choice(i));
    const std::vector<std::string> defaults{"auto -1", "jack -1", "pulse -1", "alsa -1", "null -1"};
    ASSERT_GE(offered.size(), defaults.size());
    EXPECT_EQ(std::vector<std::string>(offered.begin(), offered.begin() + 5), defaults);
    std::vector<std::string> listed;
    for (const AudioApiDevices& api : list_audio_devices())
        for (const AudioDeviceInfo& d : api.devices)
            if (d.api != "null") listed.push_back(d.api + " " + std::to_string(d.index));
    EXPECT_EQ(std::vector<std::string>(offered.begin() + 5, offered.end()), listed);

    EngineClientOptions gone;
    gone.audio = "alsa";
    gone.audio_device = 9999;
    SettingsDialog reopened(gone);
    EXPECT_EQ(reopened.options().audio.toStdString(), "alsa");
    EXPECT_EQ(reopened.options().audio_device, -1) << "a device that is gone: the API's default";
}

}  // namespace
}  // namespace archet::ui
