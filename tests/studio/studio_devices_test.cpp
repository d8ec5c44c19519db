// The studio's settings under Qt's offscreen platform: what may hold the bow is offered under
// the ids `--haptic` takes, from the list `archet devices` prints, and each one opens. A
// joystick is SDL's own virtual one (no hardware needed), as in the haptics suite.

#include <gtest/gtest.h>

#include <QComboBox>

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

TEST(SettingsDevices, TheChoicesAreTheOnesArchetDevicesLists) {
    SettingsDialog dialog(EngineClientOptions{});
    auto* haptic = dialog.findChild<QComboBox*>("haptic");
    ASSERT_NE(haptic, nullptr);
    QStringList offered;
    for (int i = 0; i < haptic->count(); ++i) offered << haptic->itemData(i).toString();
    QStringList listed{"none"};
    for (const HapticDeviceInfo& d : list_haptic_choices()) listed << QString::fromStdString(d.id);
    offered.sort(), listed.sort();
    EXPECT_EQ(offered, listed);
}

}  // namespace
}  // namespace archet::ui
