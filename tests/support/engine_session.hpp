#pragma once
// A real engine process driven as the studio drives it (tests/engine): started on a model,
// bowed from the pad or by any other means, with the status frames it has sent so far.

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "archet/link/engine_link.hpp"
#include "test_support.hpp"

namespace archet::test {

/// Waits for what the machine's speed decides (TSan on two shared cores is slow).
constexpr std::chrono::milliseconds kGenerous{60000};

class EngineSession {
  public:
    using EngineLink = link::EngineLink;
    using EngineLinkOptions = link::EngineLinkOptions;

    explicit EngineSession(const EngineLinkOptions& o = options()) : link_(o) {}

    static EngineLinkOptions options() {
        EngineLinkOptions o;
        o.archet_binary = ARCHET_BINARY;
        o.takes = std::filesystem::temp_directory_path().string();  // test::temp_dir's folders
        return o;
    }

    /// Starts the engine on a shipped model (a path under resources/) and plays it.
    bool start(const std::string& model) { return start_file(test::resource(model)); }

    bool start_file(const std::filesystem::path& model) {
        link_.start();
        if (!wait_for([&] { return link_.liveness() == EngineLink::Liveness::Running; }, kGenerous))
            return false;
        const auto loaded = link_.load_model(model.string());
        if (!await(ipc::StatusKind::ModelLoaded,
                   [&](const ipc::StatusFrame& f) { return f.sequence == loaded; }))
            return false;
        link_.play();
        return true;
    }

    // Plays `seconds` of sound (counted in the samples played, not in wall-clock time, which a
    // slow machine stretches), the pad bowing at 0.1 m/s with a slow swell of pressure (or at
    // `press`).
    void bow(double seconds, double press = 0) {
        const auto until = played_ + static_cast<std::uint64_t>(seconds * 48000);
        bow_until([&] { return played_ >= until; }, press);
    }
    // Bows on until `done` (or a generous timeout): true if it holds.
    bool bow_until(const std::function<bool()>& done, double press = 0) {
        return play_until(done, [&](double t) {
            link_.gesture(0.1 * t, press > 0 ? press : 0.0015 + 0.0005 * std::sin(3 * t));
        });
    }
    // Plays on until `done`, calling `each` with the performance's time (s, 2 ms a round).
    bool play_until(const std::function<bool()>& done, const std::function<void(double)>& each) {
        return wait_for(
            [&] {
                each(elapsed_);
                link_.heartbeat();
                drain();
                elapsed_ += 0.002;
                return done();
            },
            kGenerous);
    }

    // Waits for a status frame of `kind` that `accept`s; remembers errors on the way.
    bool await(ipc::StatusKind kind, const std::function<bool(const ipc::StatusFrame&)>& accept) {
        return wait_for(
            [&] {
                link_.heartbeat();
                return seen(kind, accept);
            },
            kGenerous);
    }
    // Reads the status frames there are now: true when one of `kind` `accept`s.
    bool seen(ipc::StatusKind kind, const std::function<bool(const ipc::StatusFrame&)>& accept) {
        ipc::StatusFrame f;
        while (status_.try_pop(f)) {
            realtime_allocations_ = f.realtime_allocations;
            if (f.kind == static_cast<std::uint32_t>(ipc::StatusKind::Error))
                errors_.push_back(f.text);
            if (f.kind == static_cast<std::uint32_t>(kind) && accept(f)) return true;
        }
        drain();
        return false;
    }

    bool await_take_written(std::string* text = nullptr) {
        return await(ipc::StatusKind::Take, [&](const ipc::StatusFrame& f) {
            const std::string said = f.text;
            if (text) *text = said;
            return said.rfind("written ", 0) == 0 || said.rfind("take failed", 0) == 0;
        });
    }

    EngineLink& link() { return link_; }
    const std::vector<std::string>& errors() const { return errors_; }
    std::uint64_t realtime_allocations() const { return realtime_allocations_; }
    std::uint64_t played() const { return played_; }
    /// The newest probe frame received.
    const ipc::ProbeFrame& latest() const { return latest_; }

  private:
    void drain() {  // the studio reads its scopes, so the engine never waits on them
        ipc::ProbeFrame p;
        while (probes_.try_pop(p)) ++played_, latest_ = p;
        ipc::ShapeFrame s;
        while (shapes_.try_pop(s)) {
        }
    }

    EngineLink link_;
    ipc::SpscRing<ipc::StatusFrame> status_ = link_.status();
    ipc::SpscRing<ipc::ProbeFrame> probes_ = link_.probes();
    ipc::SpscRing<ipc::ShapeFrame> shapes_ = link_.shapes();
    std::vector<std::string> errors_;
    std::uint64_t realtime_allocations_ = 0;  ///< as the newest status frame counts them
    std::uint64_t played_ = 0;                ///< probe frames received: samples played
    ipc::ProbeFrame latest_{};
    double elapsed_ = 0;
};

}  // namespace archet::test
