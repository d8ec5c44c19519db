#pragma once
// The studio's side of the engine: creates the shared segment, starts `archet engine` on it,
// sends commands and reads what the engine publishes. Liveness both ways: the studio's
// heartbeat counts up on every `heartbeat()`, and the engine's is watched to tell an engine
// that stopped answering from one that exited.

#include <sys/types.h>

#include <chrono>
#include <string>

#include "archet/ipc/shared_segment.hpp"
#include "archet/model/parameter_name.hpp"

namespace archet::link {

// The shared-memory protocol this link speaks (core/ipc).
using ipc::CommandFrame;
using ipc::ProbeFrame;
using ipc::SegmentHeader;
using ipc::ShapeFrame;
using ipc::SharedSegment;
using ipc::SpscRing;
using ipc::StatusFrame;

struct EngineLinkOptions {
    std::string archet_binary;    ///< the `archet` executable
    int block_frames = 64;        ///< passed to the engine's --buffer (a device may differ)
    std::string audio = "null";   ///< passed to the engine's --audio (auto: the first that opens)
    int audio_device = -1;        ///< passed to the engine's --device (−1: the API's default)
    std::string haptic = "none";  ///< passed to the engine's --haptic
    double sample_rate = 48000;   ///< Hz, passed to the engine's --rate (a device may differ)
    std::uint32_t probe_capacity = 1u << 16;
    std::chrono::milliseconds unresponsive_after{300};
    /// The take directory (absolute; created if missing): the engine records takes only in
    /// folders inside it. Empty: the engine refuses every take.
    std::string takes;
    /// The engine falls silent when the studio's heartbeat has not moved for this long (a
    /// frozen studio), plays again when it moves, and exits after `studio_give_up`.
    std::chrono::milliseconds studio_timeout{2000};
    std::chrono::milliseconds studio_give_up{60000};
    /// OSC: the UDP port the engine listens on (0: none), on the loopback address, and the
    /// HOST:PORT it sends the bow force and energy to (empty: none).
    int osc_port = 0;
    std::string osc_send;
    /// MIDI in: "" (none), "virtual" or a part of a port's name; its API (alsa, jack) and
    /// mapping file (empty: the default map).
    std::string midi;
    std::string midi_api = "alsa";
    std::string midi_map;
};

class EngineLink {
  public:
    explicit EngineLink(EngineLinkOptions options);
    ~EngineLink();  ///< asks the engine to quit, waits a little, then kills it
    EngineLink(const EngineLink&) = delete;
    EngineLink& operator=(const EngineLink&) = delete;

    /// Spawns the engine (after removing the segments of studios and engines that both died:
    /// reclaim_stale_segments); throws when it cannot. The engine is told this process's pid
    /// and watches it: it exits when the studio dies.
    void start();
    pid_t engine_pid() const { return pid_; }
    const std::string& segment_name() const { return segment_.name(); }

    /// Command helpers; each returns its sequence number (0 when the ring was full).
    std::uint32_t load_model(const std::string& path);
    std::uint32_t send_parameter(const ParameterName& name, double value);
    std::uint32_t play();
    std::uint32_t stop();
    std::uint32_t gesture(double slide, double press);
    std::uint32_t quit();
    /// Records a take into `folder` (new or empty) from the next block on, until stop_take(),
    /// a new model or a blow-up; the engine answers with Take status frames.
    std::uint32_t start_take(const std::string& folder);
    std::uint32_t stop_take();
    std::uint32_t send(CommandFrame frame);

    SpscRing<ProbeFrame> probes() { return segment_.probes(); }
    SpscRing<ShapeFrame> shapes() { return segment_.shapes(); }
    SpscRing<StatusFrame> status() { return segment_.status(); }
    SegmentHeader& header() { return segment_.header(); }
    // The device's rate and block size, as the engine wrote them into the header: the only
    // source (the options are what was asked for; a device may give something else).
    /// Hz: the rate the engine runs at, once its device is open (0 before).
    double sample_rate() { return segment_.header().sample_rate.load(); }
    /// Frames per audio block the engine runs at, once its device is open (0 before).
    std::uint32_t block_frames() { return segment_.header().block_frames.load(); }

    /// The studio is alive: call it from the GUI's timer.
    void heartbeat() { segment_.header().studio_heartbeat.fetch_add(1); }

    enum class Liveness { Starting, Running, Unresponsive, Exited };
    /// Exited: the process is gone (its status in exit_status()). Unresponsive: alive but its
    /// heartbeat has not moved for `unresponsive_after`.
    Liveness liveness();
    int exit_status() const { return exit_status_; }

  private:
    EngineLinkOptions options_;
    SharedSegment segment_;
    pid_t pid_ = -1;
    bool reaped_ = false;
    int exit_status_ = -1;
    std::uint32_t next_sequence_ = 1;
    std::uint64_t last_heartbeat_ = 0;
    std::chrono::steady_clock::time_point last_change_;
};

const char* to_string(EngineLink::Liveness);

}  // namespace archet::link
