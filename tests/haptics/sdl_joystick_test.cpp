// The SDL2 joystick backend against a real SDL joystick: a virtual one that SDL itself
// provides (no hardware needed). Its axes reach the model's gesture points through the link,
// a joystick without force feedback plays with positions only, an unplugged one goes stale,
// and bad indices are refused by name.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/haptic_choice.hpp"
#include "archet/haptic_link.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/sdl_device.hpp"
#include "test_support.hpp"
#include "virtual_joystick.hpp"

namespace archet {
namespace {

// Waits until `done` holds, up to a generous minute (SDL's event thread under TSan is slow).
template <typename Condition>
bool eventually(Condition done) {
    for (int i = 0; i < 12000 && !done(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    return done();
}

TEST(SdlJoystick, ItsAxesMoveTheGesturePoints) {
    test::VirtualJoystick stick;
    if (!stick.ready()) GTEST_SKIP() << "SDL cannot attach a virtual joystick: " << SDL_GetError();
    stick.set(0, 16384), stick.set(1, -32767);
    SdlDevice device(stick.index());
    EXPECT_FALSE(device.force_feedback()) << "a virtual joystick renders no force";
    EXPECT_EQ(device.capabilities().max_force, 0.0);
    const double range = device.capabilities().range;
    ASSERT_TRUE(eventually([&] { return std::abs(device.read().slide - 0.5 * range) < 1e-4; }))
        << "slide read " << device.read().slide;
    EXPECT_NEAR(device.read().press, -range, 1e-4);

    // Through the link, into a bowed string's gesture points.
    Model model = load_model_file(test::resource("models/bowed-string-220.json"));
    model.gesture.reset();
    Simulation sim(compile(model));
    HapticLink link(device);
    const double period = 16 / sim.sample_rate();
    for (int n = 0; n < 4800; ++n) {
        if (n % 16 == 0) link.tick(sim, sim.time(), period);
        device.write(0, 0, sim.time());
        sim.step();
    }
    EXPECT_EQ(link.stale_ticks(), 0u);
    EXPECT_NEAR(sim.position(sim.model().mat_slots.at("hand_slide")), 0.5 * range, 1e-4);
    EXPECT_EQ(link.last_force().slide, 0.0) << "positions only: no force is sent";

    stick.set(0, -32767);
    EXPECT_TRUE(eventually([&] { return std::abs(device.read().slide + range) < 1e-4; }))
        << "follows the stick";
}

TEST(SdlJoystick, AnUnpluggedJoystickGoesStale) {
    test::VirtualJoystick stick;
    if (!stick.ready()) GTEST_SKIP() << "SDL cannot attach a virtual joystick: " << SDL_GetError();
    SdlDevice device(stick.index());
    EXPECT_TRUE(eventually([&] { return !device.stale(0, 0.02); }));
    stick.unplug();
    EXPECT_TRUE(eventually([&] { return device.stale(0, 0.02); }))
        << "its I/O thread stops answering once the joystick is gone";
}

TEST(SdlJoystick, BadIndicesAreRefusedByName) {
    try {
        SdlDevice device(99);
        FAIL() << "opened a joystick that does not exist";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("--haptic sdl:99"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("there is no joystick 99"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(open_haptic_device("sdl:first"), InputError);
    EXPECT_THROW(open_haptic_device("sdl:"), InputError);
}

TEST(SdlJoystick, DevicesListsIt) {
    test::VirtualJoystick stick;
    if (!stick.ready()) GTEST_SKIP() << "SDL cannot attach a virtual joystick: " << SDL_GetError();
    const auto found = list_sdl_joysticks();
    ASSERT_FALSE(found.empty());
    const HapticDeviceInfo& listed = found.back();
    EXPECT_EQ(listed.id(), "sdl:" + std::to_string(stick.index()));
    EXPECT_FALSE(listed.force_feedback);
    EXPECT_EQ(listed.axes, 2);
    EXPECT_NE(describe(listed).find("(positions only)"), std::string::npos) << describe(listed);
    EXPECT_EQ(describe(listed).rfind("sdl " + std::to_string(stick.index()) + ": ", 0), 0u)
        << describe(listed);
    const auto choices = list_haptic_choices();
    EXPECT_TRUE(std::any_of(choices.begin(), choices.end(), [&](const HapticDeviceInfo& d) {
        return d.id() == listed.id();
    })) << "among the choices the studio offers";
    const HapticChoice opened = open_haptic_device(listed.id());
    ASSERT_NE(opened.device, nullptr) << "--haptic " << listed.id() << " opens it";
    EXPECT_NE(opened.note.find("no force feedback"), std::string::npos) << opened.note;
}

}  // namespace
}  // namespace archet
