#include "archet/link/engine_link.hpp"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

extern char** environ;

namespace archet::link {

using ipc::kTextSize;
using ipc::Opcode;
using ipc::plan_layout;

namespace {
constexpr std::uint32_t kCommandCapacity = 256, kShapeCapacity = 64, kStatusCapacity = 256;

std::string seconds(std::chrono::milliseconds ms) {
    std::ostringstream s;
    s << std::chrono::duration<double>(ms).count();
    return s.str();
}
}  // namespace

EngineLink::EngineLink(EngineLinkOptions options)
    : options_(std::move(options)),
      segment_(SharedSegment::create(plan_layout(kCommandCapacity, options_.probe_capacity,
                                                 kShapeCapacity, kStatusCapacity))) {}

EngineLink::~EngineLink() {
    if (pid_ <= 0 || reaped_) return;
    quit();
    for (int i = 0; i < 100 && liveness() != Liveness::Exited; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (!reaped_) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, nullptr, 0);
    }
}

void EngineLink::start() {
    ipc::reclaim_stale_segments();
    const std::string block = std::to_string(options_.block_frames);
    std::ostringstream rate;
    rate << options_.sample_rate;
    std::vector<std::string> args{options_.archet_binary,
                                  "engine",
                                  "--shm",
                                  segment_.name(),
                                  "--buffer",
                                  block,
                                  "--haptic",
                                  options_.haptic,
                                  "--audio",
                                  options_.audio,
                                  "--device",
                                  std::to_string(options_.audio_device),
                                  "--rate",
                                  rate.str(),
                                  "--studio-pid",
                                  std::to_string(::getpid()),
                                  "--studio-timeout",
                                  seconds(options_.studio_timeout),
                                  "--studio-give-up",
                                  seconds(options_.studio_give_up)};
    if (!options_.takes.empty()) args.insert(args.end(), {"--takes", options_.takes});
    if (options_.osc_port > 0)
        args.insert(args.end(), {"--osc", std::to_string(options_.osc_port)});
    if (!options_.osc_send.empty()) args.insert(args.end(), {"--osc-send", options_.osc_send});
    if (!options_.midi.empty())
        args.insert(args.end(), {"--midi", options_.midi, "--midi-api", options_.midi_api});
    if (!options_.midi_map.empty()) args.insert(args.end(), {"--midi-map", options_.midi_map});
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int error = ::posix_spawn(&pid_, options_.archet_binary.c_str(), nullptr, nullptr,
                                    argv.data(), environ);
    if (error != 0)
        throw std::runtime_error("cannot start the engine: " + std::string(std::strerror(error)));
    last_change_ = std::chrono::steady_clock::now();
}

std::uint32_t EngineLink::send(CommandFrame frame) {
    frame.sequence = next_sequence_++;
    return segment_.commands().try_push(frame) ? frame.sequence : 0;
}

namespace {
CommandFrame command(Opcode op, const std::string& text = "", double value = 0) {
    CommandFrame f{};
    f.opcode = static_cast<std::uint32_t>(op);
    f.value = value;
    std::strncpy(f.text, text.c_str(), kTextSize - 1);
    return f;
}
}  // namespace

std::uint32_t EngineLink::load_model(const std::string& path) {
    return send(command(Opcode::LoadModel, path));
}
std::uint32_t EngineLink::send_parameter(const ParameterName& name, double value) {
    return send(command(Opcode::SetParameter, name.text(), value));
}
std::uint32_t EngineLink::play() {
    return send(command(Opcode::Play));
}
std::uint32_t EngineLink::stop() {
    return send(command(Opcode::Stop));
}
std::uint32_t EngineLink::quit() {
    return send(command(Opcode::Quit));
}
std::uint32_t EngineLink::start_take(const std::string& folder) {
    return send(command(Opcode::StartTake, folder));
}
std::uint32_t EngineLink::stop_take() {
    return send(command(Opcode::StopTake));
}
std::uint32_t EngineLink::gesture(double slide, double press) {
    CommandFrame f = command(Opcode::Gesture);
    f.slide = slide, f.press = press;
    return send(f);
}

EngineLink::Liveness EngineLink::liveness() {
    if (pid_ <= 0) return Liveness::Exited;
    if (!reaped_) {
        int status = 0;
        if (::waitpid(pid_, &status, WNOHANG) == pid_) {
            reaped_ = true;
            exit_status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        }
    }
    if (reaped_) return Liveness::Exited;
    const std::uint64_t beat = segment_.header().engine_heartbeat.load();
    const auto now = std::chrono::steady_clock::now();
    if (beat != last_heartbeat_) {
        last_heartbeat_ = beat;
        last_change_ = now;
    }
    if (beat == 0)
        return now - last_change_ > std::chrono::seconds(5) ? Liveness::Unresponsive
                                                            : Liveness::Starting;
    return now - last_change_ > options_.unresponsive_after ? Liveness::Unresponsive
                                                            : Liveness::Running;
}

const char* to_string(EngineLink::Liveness l) {
    switch (l) {
        case EngineLink::Liveness::Starting:
            return "starting";
        case EngineLink::Liveness::Running:
            return "running";
        case EngineLink::Liveness::Unresponsive:
            return "unresponsive";
        case EngineLink::Liveness::Exited:
            return "exited";
    }
    return "?";
}

}  // namespace archet::link
