#pragma once
// A joystick SDL itself provides (no hardware needed), for the suites that play through the
// SDL backend or list it: the haptics suite and the studio's settings.

#include <SDL.h>

namespace archet::test {

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

}  // namespace archet::test
