#include "live_play.hpp"

#include <chrono>
#include <filesystem>
#include <iostream>
#include <thread>

#include "archet/common/input_error.hpp"
#include "archet/interruption.hpp"
#include "archet/link/engine_link.hpp"
#include "archet/midi/midi_mapping.hpp"
#include "model_loading.hpp"

namespace archet::cli {

namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kEngineStart = std::chrono::seconds(30);

// The engine's status frames since the last call: errors and take news said on stderr; the
// frame `wanted` (kind and sequence) reported when it came.
class StatusReader {
  public:
    explicit StatusReader(link::EngineLink& link)
        : link_(link), status_(link.status()), probes_(link.probes()), shapes_(link.shapes()) {}

    // Drains what came; true when a frame of `kind` answered command `sequence` (or, with
    // sequence 0, any frame of `kind` whose text starts with `prefix`).
    bool read(ipc::StatusKind kind, std::uint32_t sequence = 0, const std::string& prefix = "") {
        bool seen = false;
        ipc::StatusFrame f;
        while (status_.try_pop(f)) {
            const std::string text = f.text;
            const auto k = static_cast<ipc::StatusKind>(f.kind);
            if (k == ipc::StatusKind::Error) {
                std::cerr << "archet: " << text << "\n";
                if (sequence != 0 && f.sequence == sequence) refused_ = text;
            }
            if (k == ipc::StatusKind::Take || k == ipc::StatusKind::Blowup)
                std::cerr << "archet: " << (k == ipc::StatusKind::Take ? "take " : "") << text
                          << "\n";
            if (k == ipc::StatusKind::Take &&
                (text.rfind("written ", 0) == 0 || text.rfind("take failed", 0) == 0)) {
                take_done_ = true;  // whenever it comes: the engine may end a take itself
                take_whole_ = text.rfind("written ", 0) == 0 &&
                              text.find("; incomplete:") == std::string::npos;
            }
            if (k == ipc::StatusKind::Heartbeat && device_.empty()) device_ = text;
            if (k == kind && (sequence ? f.sequence == sequence : text.rfind(prefix, 0) == 0))
                seen = true, said_ = text;
        }
        ipc::ProbeFrame p;  // the scopes nobody watches: read, so the engine never waits
        while (probes_.try_pop(p)) {
        }
        ipc::ShapeFrame s;
        while (shapes_.try_pop(s)) {
        }
        return seen;
    }
    // Keeps the heartbeat and reads until `done` or `timeout`; false on timeout or an engine
    // that exited.
    template <class Done>
    bool until(Done done, Clock::duration timeout) {
        const auto end = Clock::now() + timeout;
        while (Clock::now() < end && !interruption_signal()) {
            link_.heartbeat();
            if (done()) return true;
            if (link_.liveness() == link::EngineLink::Liveness::Exited) return false;
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        return false;
    }
    const std::string& refused() const { return refused_; }
    bool take_done() const { return take_done_; }
    /// Whether the take the engine finished holds all that was played (not lost, not failed).
    bool take_whole() const { return take_whole_; }
    const std::string& said() const { return said_; }
    const std::string& device() const { return device_; }

  private:
    link::EngineLink& link_;
    ipc::SpscRing<ipc::StatusFrame> status_;
    ipc::SpscRing<ipc::ProbeFrame> probes_;
    ipc::SpscRing<ipc::ShapeFrame> shapes_;
    std::string refused_, said_, device_;
    bool take_done_ = false, take_whole_ = false;
};

link::EngineLinkOptions engine_options(const LivePlayArguments& a) {
    link::EngineLinkOptions o;
    o.archet_binary = std::filesystem::read_symlink("/proc/self/exe").string();
    o.audio = a.audio.api, o.audio_device = a.audio.device;
    o.block_frames = a.audio.buffer_frames, o.sample_rate = a.audio.sample_rate;
    o.haptic = a.haptic;
    o.osc_port = a.osc_port;
    o.midi = a.midi, o.midi_api = a.midi_api, o.midi_map = a.midi_map;
    // The engine records takes only inside its take directory: the take's own parent.
    if (!a.take.empty())
        o.takes = std::filesystem::absolute(a.take).lexically_normal().parent_path().string();
    return o;
}

}  // namespace

int run_live_play(const LivePlayArguments& a) {
    const InterruptionGuard stop_on_signal;  // SIGINT, SIGTERM, SIGHUP: stop, finish the take
    // What the engine would refuse is refused here first, with play's own status (2).
    load_validated_model(a.model, {});
    if (!a.midi_map.empty()) midi::load_midi_mapping(a.midi_map);
    if (!a.take.empty() && std::filesystem::exists(a.take))
        throw InputError("--take " + a.take, "exists already; give a new folder");
    link::EngineLink link(engine_options(a));
    link.start();
    StatusReader engine(link);
    if (!engine.until([&] { return link.liveness() == link::EngineLink::Liveness::Running; },
                      kEngineStart))
        throw std::runtime_error("the engine did not start (exit status " +
                                 std::to_string(link.exit_status()) + ")");
    const std::uint32_t loaded =
        link.load_model(std::filesystem::absolute(a.model).lexically_normal().string());
    if (!engine.until(
            [&] {
                return engine.read(ipc::StatusKind::ModelLoaded, loaded) ||
                       !engine.refused().empty();
            },
            kEngineStart) ||
        !engine.refused().empty())
        throw InputError(
            a.model, engine.refused().empty() ? "the engine did not load it" : engine.refused());
    // The engine's own line: its device, and OSC or MIDI it could not open ("no MIDI: ...").
    engine.until(
        [&] {
            engine.read(ipc::StatusKind::Heartbeat);
            return !engine.device().empty();
        },
        kEngineStart);
    std::cerr << "archet: engine: " << engine.device() << "\n";
    link.play();
    if (!a.take.empty()) link.start_take(std::filesystem::absolute(a.take).string());
    std::cerr << "archet: playing " << a.model << " live"
              << (a.osc_port ? ", OSC on 127.0.0.1:" + std::to_string(a.osc_port) : "")
              << (a.midi.empty() ? "" : ", MIDI from " + a.midi + " (" + a.midi_api + ")")
              << (a.duration > 0 ? "" : "; Ctrl-C ends") << "\n";
    const auto length = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(a.duration > 0 ? a.duration : 1e9));
    engine.until(
        [&] {
            engine.read(ipc::StatusKind::Heartbeat);
            return false;  // plays on: the duration, a signal or the engine's exit ends it
        },
        length);
    const bool engine_lost = link.liveness() == link::EngineLink::Liveness::Exited;
    const int signal = interruption_signal();
    bool take_failed = false;
    if (!a.take.empty() && !engine_lost) {
        link.stop_take();
        // The engine finishes the take; waited for even after Ctrl-C (a second one kills).
        const auto end = Clock::now() + kEngineStart;
        bool written = false;
        while (!written && Clock::now() < end &&
               link.liveness() != link::EngineLink::Liveness::Exited) {
            link.heartbeat();
            engine.read(ipc::StatusKind::Take);
            written = engine.take_done();
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        if (!written) std::cerr << "archet: the take was not finished in time\n";
        take_failed = !written || !engine.take_whole();
    }
    if (engine_lost)
        throw std::runtime_error("the engine exited (status " + std::to_string(link.exit_status()) +
                                 ")");
    if (signal) return 128 + signal;
    return take_failed ? 1 : 0;  // a take not written whole is not what was asked
}

}  // namespace archet::cli
