#include "archet/sdl_device.hpp"

#include <SDL.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>

#include "archet/common/input_error.hpp"

namespace archet {

namespace {

// Joystick and haptic subsystems, held for as long as the object lives (SDL counts them).
class SdlSubsystems {
  public:
    SdlSubsystems() {
        if (SDL_InitSubSystem(SDL_INIT_JOYSTICK) != 0) return;
        flags_ = SDL_INIT_JOYSTICK;
        // Force feedback is optional: a joystick without it still plays with positions.
        if (SDL_InitSubSystem(SDL_INIT_HAPTIC) == 0) flags_ |= SDL_INIT_HAPTIC;
    }
    ~SdlSubsystems() {
        if (flags_) SDL_QuitSubSystem(flags_);
    }
    SdlSubsystems(const SdlSubsystems&) = delete;
    SdlSubsystems& operator=(const SdlSubsystems&) = delete;
    bool joystick() const { return flags_ & SDL_INIT_JOYSTICK; }
    bool haptic() const { return flags_ & SDL_INIT_HAPTIC; }

  private:
    Uint32 flags_ = 0;
};

SDL_HapticEffect constant_force(int axis, Sint16 level) {
    SDL_HapticEffect effect{};
    effect.type = SDL_HAPTIC_CONSTANT;
    effect.constant.direction.type = SDL_HAPTIC_CARTESIAN;
    effect.constant.direction.dir[axis] = 1;
    effect.constant.length = SDL_HAPTIC_INFINITY;
    effect.constant.level = level;
    return effect;
}

}  // namespace

struct SdlDevice::Session {
    SdlSubsystems subsystems;
    SDL_Joystick* joystick = nullptr;
    SDL_Haptic* haptic = nullptr;
    int effect[2] = {-1, -1};

    ~Session() {
        if (haptic) {
            for (int id : effect)
                if (id >= 0) SDL_HapticDestroyEffect(haptic, id);
            SDL_HapticClose(haptic);
        }
        if (joystick) SDL_JoystickClose(joystick);
    }

    void send(double slide, double press, double max_force) {
        if (!haptic) return;
        const double forces[2] = {slide, press};
        for (int a = 0; a < 2; ++a) {
            const double level = std::clamp(forces[a] / max_force, -1.0, 1.0) * 0x7fff;
            SDL_HapticEffect e = constant_force(a, static_cast<Sint16>(std::lround(level)));
            SDL_HapticUpdateEffect(haptic, effect[a], &e);  // a failed update retries next tick
        }
    }
};

SdlDevice::SdlDevice(int index, SdlOptions options) : options_(options) {
    // SDL is opened on the I/O thread, which owns it from then on; wait for its verdict.
    std::promise<std::string> opened;
    std::future<std::string> verdict = opened.get_future();
    io_ = std::thread([this, index, &opened] {
        Session session;
        auto refuse = [&](const std::string& why) { opened.set_value(why); };
        if (!session.subsystems.joystick())
            return refuse(std::string("SDL has no joystick support here: ") + SDL_GetError());
        const int count = SDL_NumJoysticks();
        if (index < 0 || index >= count)
            return refuse("there is no joystick " + std::to_string(index) + "; SDL finds " +
                          std::to_string(std::max(count, 0)) + " (see archet devices)");
        session.joystick = SDL_JoystickOpen(index);
        if (!session.joystick)
            return refuse(std::string("cannot open the joystick: ") + SDL_GetError());
        const char* name = SDL_JoystickName(session.joystick);
        capabilities_.name = name ? name : "SDL joystick " + std::to_string(index);
        if (SDL_JoystickNumAxes(session.joystick) < 2)
            return refuse("\"" + capabilities_.name + "\" has fewer than two axes");
        if (session.subsystems.haptic() && SDL_JoystickIsHaptic(session.joystick) == 1) {
            session.haptic = SDL_HapticOpenFromJoystick(session.joystick);
            if (session.haptic && !(SDL_HapticQuery(session.haptic) & SDL_HAPTIC_CONSTANT)) {
                SDL_HapticClose(session.haptic);
                session.haptic = nullptr;
            }
        }
        for (int a = 0; session.haptic && a < 2; ++a) {
            SDL_HapticEffect e = constant_force(a, 0);
            session.effect[a] = SDL_HapticNewEffect(session.haptic, &e);
            if (session.effect[a] < 0 || SDL_HapticRunEffect(session.haptic, session.effect[a], 1))
                return refuse(std::string("cannot start a force effect: ") + SDL_GetError());
        }
        capabilities_.range = options_.range;
        capabilities_.max_force = session.haptic ? options_.max_force : 0.0;
        capabilities_.force_rate = session.haptic ? options_.update_rate : 0.0;
        capabilities_.position_rate = options_.update_rate;
        answered();
        opened.set_value("");
        io_loop_with(session);
    });
    const std::string why = verdict.get();
    if (!why.empty()) {
        io_.join();
        throw InputError("--haptic sdl:" + std::to_string(index), why);
    }
}

SdlDevice::~SdlDevice() {
    running_.store(false);
    if (io_.joinable()) io_.join();
}

void SdlDevice::io_loop_with(Session& session) {
    const auto period = std::chrono::duration<double>(1.0 / options_.update_rate);
    auto next = std::chrono::steady_clock::now();
    while (running_.load()) {
        SDL_JoystickUpdate();
        if (!SDL_JoystickGetAttached(session.joystick)) break;  // unplugged: the link sees it stale
        for (int a = 0; a < 2; ++a) {
            const double unit =
                std::clamp(SDL_JoystickGetAxis(session.joystick, a) / 32767.0, -1.0, 1.0);
            publish_position(a, unit * options_.range);
        }
        answered();
        double slide = 0, press = 0;
        forces_to_send(options_.write_timeout, slide, press);
        session.send(slide, press, options_.max_force);
        next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(period);
        std::this_thread::sleep_until(next);
    }
    session.send(0, 0, options_.max_force);
}

std::vector<HapticDeviceInfo> list_sdl_joysticks() {
    std::vector<HapticDeviceInfo> found;
    SdlSubsystems subsystems;
    if (!subsystems.joystick()) return found;
    for (int i = 0; i < SDL_NumJoysticks(); ++i) {
        SDL_Joystick* joystick = SDL_JoystickOpen(i);
        if (!joystick) continue;
        if (const int axes = SDL_JoystickNumAxes(joystick); axes >= 2) {
            bool force = false;
            if (subsystems.haptic() && SDL_JoystickIsHaptic(joystick) == 1) {
                if (SDL_Haptic* haptic = SDL_HapticOpenFromJoystick(joystick)) {
                    force = SDL_HapticQuery(haptic) & SDL_HAPTIC_CONSTANT;
                    SDL_HapticClose(haptic);
                }
            }
            const char* name = SDL_JoystickName(joystick);
            const std::string index = std::to_string(i);
            found.push_back({"sdl", index, name ? name : "joystick", axes, force});
        }
        SDL_JoystickClose(joystick);
    }
    return found;
}

}  // namespace archet
