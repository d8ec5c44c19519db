// The SDL2 joystick backend against a real SDL joystick: a virtual one that SDL itself
// provides (no hardware needed). Its axes reach the model's gesture points through the link,
// a joystick without force feedback plays with positions only, an unplugged one goes stale,
// and bad indices are refused by name.

#include <SDL.h>
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/haptic_choice.hpp"
#include "archet/haptic_link.hpp"
#include "archet/physics/compiled_model.hpp"
#include "archet/sdl_device.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

// A two-axis virtual joystick, attached for the test's lifetime.
class VirtualJoystick {
  public:
    VirtualJoystick() {
        if (SDL_InitSubSystem(SDL_INIT_JOYSTICK) != 0) return;
        index_ = SDL_JoystickAttachVirtual(SDL_JOYSTICK_TYPE_GAMECONTROLLER, 2, 0, 0);
        if (index_ >= 0) joystick_ = SDL_JoystickOpen(index_);
    }
    ~VirtualJoystick() {
        unplug();
        SDL_QuitSubSystem(SDL_INIT_JOYSTICK);
    }
    bool ready() const { return joystick_ != nullptr; }
    int index() const { return index_; }
    void set(int axis, Sint16 value) { SDL_JoystickSetVirtualAxis(joystick_, axis, value); }
    void unplug() {
        if (!joystick_) return;
        SDL_JoystickClose(joystick_);
        SDL_JoystickDetachVirtual(index_);
        joystick_ = nullptr;
    }

  private:
    int index_ = -1;
    SDL_Joystick* joystick_ = nullptr;
};

// Waits until `done` holds, up to a generous minute (SDL's event thread under TSan is slow).
template <typename Condition>
bool eventually(Condition done) {
    for (int i = 0; i < 12000 && !done(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    return done();
}

TEST(SdlJoystick, ItsAxesMoveTheGesturePoints) {
    VirtualJoystick stick;
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
    VirtualJoystick stick;
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
    VirtualJoystick stick;
    if (!stick.ready()) GTEST_SKIP() << "SDL cannot attach a virtual joystick: " << SDL_GetError();
    const auto found = list_sdl_joysticks();
    ASSERT_FALSE(found.empty());
    EXPECT_NE(found.back().find("(positions only)"), std::string::npos) << found.back();
    EXPECT_EQ(found.back().rfind("sdl " + std::to_string(stick.index()) + ": ", 0), 0u)
        << found.back();
}

}  // namespace
}  // namespace archet
