#include "archet/evdev_device.hpp"

#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <linux/input.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <vector>

#include "archet/common/input_error.hpp"

namespace archet {

namespace {

// Direction of a constant force, in the kernel's encoding: 0x4000 left, 0xC000 right, 0 down.
constexpr unsigned short kDirection[2] = {0xC000, 0x0000};

}  // namespace

EvdevDevice::EvdevDevice(const std::string& path, EvdevOptions options)
    : path_(path), options_(options) {
    const std::string where = "--haptic evdev:" + path;
    fd_ = ::open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0)
        throw InputError(where, std::string("cannot open the device: ") + std::strerror(errno));
    const int rc = libevdev_new_from_fd(fd_, &device_);
    if (rc < 0) {
        ::close(fd_);
        throw InputError(where, std::string("not an input device: ") + std::strerror(-rc));
    }
    auto refuse = [&](const std::string& why) {
        libevdev_free(device_);
        ::close(fd_);
        throw InputError(where, why);
    };
    const char* name = libevdev_get_name(device_);
    capabilities_.name = name ? name : path;
    const unsigned axes[2] = {ABS_X, ABS_Y};
    for (int a = 0; a < 2; ++a) {
        if (!libevdev_has_event_code(device_, EV_ABS, axes[a]))
            refuse("\"" + capabilities_.name + "\" has no absolute " + (a == 0 ? "X" : "Y") +
                   " axis; a 2-axis joystick is needed");
        minimum_[a] = libevdev_get_abs_minimum(device_, axes[a]);
        maximum_[a] = libevdev_get_abs_maximum(device_, axes[a]);
        if (maximum_[a] <= minimum_[a])
            refuse("axis range of \"" + capabilities_.name + "\" is empty");
    }
    if (!libevdev_has_event_code(device_, EV_FF, FF_CONSTANT))
        refuse("\"" + capabilities_.name + "\" has no constant-force feedback (FF_CONSTANT)");
    for (int a = 0; a < 2; ++a) {
        ff_effect effect{};
        effect.type = FF_CONSTANT;
        effect.id = -1;
        effect.direction = kDirection[a];
        effect.replay.length = 0;  // until stopped
        effect.u.constant.level = 0;
        if (::ioctl(fd_, EVIOCSFF, &effect) < 0)
            refuse(std::string("cannot upload a force effect: ") + std::strerror(errno));
        effect_[a] = effect.id;
        input_event play{};
        play.type = EV_FF;
        play.code = static_cast<unsigned short>(effect.id);
        play.value = 1;
        if (::write(fd_, &play, sizeof play) != static_cast<ssize_t>(sizeof play))
            refuse(std::string("cannot start a force effect: ") + std::strerror(errno));
    }
    capabilities_.range = options_.range;
    capabilities_.max_force = options_.max_force;
    capabilities_.force_rate = options_.update_rate;
    capabilities_.position_rate = options_.update_rate;
    answered();
    running_.store(true);
    io_ = std::thread([this] { io_loop(); });
}

EvdevDevice::~EvdevDevice() {
    running_.store(false);
    if (io_.joinable()) io_.join();
    send_levels(0, 0);
    for (int id : effect_)
        if (id >= 0) ::ioctl(fd_, EVIOCRMFF, id);
    libevdev_free(device_);
    ::close(fd_);
}

void EvdevDevice::send_levels(double slide, double press) {
    const double forces[2] = {slide, press};
    for (int a = 0; a < 2; ++a) {
        if (effect_[a] < 0) continue;
        ff_effect effect{};
        effect.type = FF_CONSTANT;
        effect.id = static_cast<short>(effect_[a]);
        effect.direction = kDirection[a];
        const double level = std::clamp(forces[a] / options_.max_force, -1.0, 1.0) * 0x7fff;
        effect.u.constant.level = static_cast<short>(std::lround(level));
        ::ioctl(fd_, EVIOCSFF,
                &effect);  // the newest value only; a failed update is retried next tick
    }
}

void EvdevDevice::io_loop() {
    const auto period = std::chrono::duration<double>(1.0 / options_.update_rate);
    auto next = std::chrono::steady_clock::now();
    while (running_.load()) {
        input_event event{};
        int rc;
        while ((rc = libevdev_next_event(device_, LIBEVDEV_READ_FLAG_NORMAL, &event)) >= 0) {
            if (rc == LIBEVDEV_READ_STATUS_SYNC)
                continue;  // dropped events: the state is resynced below
            if (event.type != EV_ABS || (event.code != ABS_X && event.code != ABS_Y)) continue;
            const int a = event.code == ABS_X ? 0 : 1;
            const double unit =
                2.0 * (event.value - minimum_[a]) / (maximum_[a] - minimum_[a]) - 1.0;  // −1 … 1
            publish_position(a, unit * options_.range);
        }
        if (rc != -EAGAIN && rc != -EINTR)
            break;  // unplugged: stop answering, the link sees it stale
        answered();
        double slide = 0, press = 0;
        forces_to_send(options_.write_timeout, slide, press);
        send_levels(slide, press);
        next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(period);
        std::this_thread::sleep_until(next);
    }
    send_levels(0, 0);
}

std::vector<HapticDeviceInfo> list_evdev_devices() {
    std::vector<HapticDeviceInfo> found;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator("/dev/input", ec)) {
        const std::string path = entry.path().string();
        if (path.find("/event") == std::string::npos) continue;
        const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
        if (fd < 0) continue;
        libevdev* dev = nullptr;
        if (libevdev_new_from_fd(fd, &dev) == 0) {
            if (libevdev_has_event_code(dev, EV_ABS, ABS_X) &&
                libevdev_has_event_code(dev, EV_ABS, ABS_Y) &&
                libevdev_has_event_code(dev, EV_FF, FF_CONSTANT)) {
                int axes = 0;
                for (unsigned code = 0; code <= ABS_MAX; ++code)
                    axes += libevdev_has_event_code(dev, EV_ABS, code);
                found.push_back({"evdev", path, libevdev_get_name(dev), axes, true});
            }
            libevdev_free(dev);
        }
        ::close(fd);
    }
    std::sort(found.begin(), found.end(),
              [](const HapticDeviceInfo& a, const HapticDeviceInfo& b) { return a.id() < b.id(); });
    return found;
}

}  // namespace archet
