// Takes recorded through the shared-memory protocol: the studio starts one in the middle of
// a performance, changes a parameter while it records and stops it; `archet render --take`
// then reproduces the take's audio to the byte from the state where it began. A take refuses
// a folder that holds files and ends when a new model is loaded; an engine told to stop
// finishes its take, one killed outright leaves a take `render --take` recovers, and a take
// that clips says so.

#include <gtest/gtest.h>

#include <signal.h>
#include <sndfile.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <thread>

#include "archet/files/take_file.hpp"
#include "archet/link/engine_link.hpp"
#include "engine_session.hpp"
#include "take_file_support.hpp"
#include "test_support.hpp"

namespace archet::ipc {
namespace {

using link::EngineLink;
using link::EngineLinkOptions;

using test::read_json;
using test::samples_of;
using test::size_of;

using namespace std::chrono_literals;

using test::wait_for;

using test::EngineSession;
using test::kGenerous;

// Re-renders the take in `dir`/take and expects take.wav to the byte.
void expect_replayed(const std::filesystem::path& dir, const char* why) {
    const auto r = test::run_archet(
        {"render", "--take", (dir / "take").string(), "-o", (dir / "again.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(test::read_file(dir / "again.wav"), test::read_file(dir / "take" / "take.wav"))
        << why;
}

// Re-renders the take's probes and expects its probes.csv to the byte, times included.
void expect_probes_replayed(const std::filesystem::path& dir) {
    const auto r =
        test::run_archet({"render", "--take", (dir / "take").string(), "--probes",
                          (dir / "again.csv").string(), "-o", (dir / "again-too.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(test::read_file(dir / "again.csv"), test::read_file(dir / "take" / "probes.csv"))
        << "the take's probes re-render to the byte, times included";
}

TEST(EngineTake, StartedMidPerformanceReRendersToTheByte) {
    const auto dir = test::temp_dir("engine-take");
    EngineSession engine;
    ASSERT_TRUE(engine.start("models/bowed-string-220.json"));
    engine.bow(0.5);  // the string is sounding when the take starts

    const auto started = engine.link().start_take((dir / "take").string());
    ASSERT_TRUE(engine.await(StatusKind::Take, [&](const StatusFrame& f) {
        return f.sequence == started && std::string(f.text).rfind("recording ", 0) == 0;
    })) << (engine.errors().empty() ? "" : engine.errors()[0]);
    engine.bow(0.4);
    engine.link().send_parameter({"friction", "mu_s"}, 0.7);  // recorded, and replayed
    engine.bow(0.4);
    engine.link().stop_take();
    std::string said;
    ASSERT_TRUE(engine.await_take_written(&said)) << said;
    EXPECT_TRUE(engine.errors().empty()) << engine.errors()[0];
    EXPECT_EQ(engine.realtime_allocations(), 0u)
        << "saving the state and feeding the take allocate nothing on the real-time thread";

    const TakeDescription take = read_take_file(dir / "take" / "take.json");
    EXPECT_TRUE(take.has_state) << "it began mid-performance";
    EXPECT_TRUE(take.has_parameters);
    EXPECT_GT(take.start_tick, 10000u);
    EXPECT_GT(take.frames, 20000u);
    expect_replayed(dir, "the re-rendered take differs");
    // Its probes too, the energy at every sample, which the engine's runs read while it records
    // (the scopes get it at every 16th).
    expect_probes_replayed(dir);
}

// The studio's bow position (the parameter `bow.position`, as the inspector and OSC's
// /archet/param send it) moves the bow of the playing string: the model with its bow elsewhere
// takes over the string's whole motion, its clock included, instead of starting again from rest;
// the bow bows on; the take keeps the move and re-renders to the byte. A β out of range is
// refused with a sentence and moves nothing.
TEST(EngineTake, TheStudiosBowPositionMovesTheBowOfThePlayingString) {
    const auto dir = test::temp_dir("engine-take-bow-move");
    EngineSession engine;
    ASSERT_TRUE(engine.start("models/bowed-string-220.json"));
    engine.bow(0.5);
    const auto started = engine.link().start_take((dir / "take").string());
    ASSERT_TRUE(engine.await(StatusKind::Take, [&](const StatusFrame& f) {
        return f.sequence == started && std::string(f.text).rfind("recording ", 0) == 0;
    })) << (engine.errors().empty() ? "" : engine.errors()[0]);
    engine.bow(0.2);
    const std::uint64_t tick = engine.latest().tick;
    engine.link().send_parameter({"bow", "position"}, 0.3);  // from the model's 0.115
    engine.bow(0.4);
    EXPECT_GT(engine.latest().tick, tick + 0.3 * 48000)
        << "the moved model counts on from the playing one's clock";
    EXPECT_GT(std::abs(engine.latest().values[5]), 0.0) << "still bowing: friction";
    EXPECT_GT(engine.latest().values[4], 0.01) << "and pressed in";
    const auto refused = engine.link().send_parameter({"bow", "position"}, 0.7);
    ASSERT_TRUE(engine.await(StatusKind::Error,
                             [&](const StatusFrame& f) { return f.sequence == refused; }));
    EXPECT_NE(engine.errors().back().find("β must be in (0, 0.5)"), std::string::npos)
        << engine.errors().back();
    engine.bow(0.1);
    engine.link().stop_take();
    std::string said;
    ASSERT_TRUE(engine.await_take_written(&said)) << said;
    EXPECT_EQ(engine.errors().size(), 1u) << engine.errors().front();
    EXPECT_EQ(engine.realtime_allocations(), 0u);

    const auto changes = read_parameter_changes(dir / "take" / "parameters.json");
    ASSERT_EQ(changes.size(), 1u) << "the move, and not the refused β";
    EXPECT_EQ(changes[0].parameter, "bow.position");
    EXPECT_DOUBLE_EQ(changes[0].value, 0.3);
    expect_replayed(dir, "the take across the move re-renders to the byte");
}

// The engine runs the string in runs of up to the hand's next tick (Simulation::run(), the
// bowed chain's own loop, reading the probes); without an energy probe, they read no energy:
// the take still re-renders tick by tick to the byte, its sound and every probe.
TEST(EngineTake, PlayedInRunsReRendersToTheByte) {
    const auto dir = test::temp_dir("engine-take-runs");
    nlohmann::json model = read_json(test::resource("models/bowed-string-220.json"));
    auto& probes = model["probes"];
    probes.erase(std::remove_if(probes.begin(), probes.end(),
                                [](const nlohmann::json& p) { return p["kind"] == "energy"; }),
                 probes.end());
    ASSERT_GE(probes.size(), 8u);
    std::ofstream(dir / "string.json") << model.dump(2);
    EngineSession engine;
    ASSERT_TRUE(engine.start_file(dir / "string.json"));
    engine.bow(0.3);
    const auto started = engine.link().start_take((dir / "take").string());
    ASSERT_TRUE(engine.await(StatusKind::Take, [&](const StatusFrame& f) {
        return f.sequence == started && std::string(f.text).rfind("recording ", 0) == 0;
    })) << (engine.errors().empty() ? "" : engine.errors()[0]);
    engine.bow(0.5);
    engine.link().stop_take();
    std::string said;
    ASSERT_TRUE(engine.await_take_written(&said)) << said;
    EXPECT_EQ(engine.realtime_allocations(), 0u);
    expect_replayed(dir, "the re-rendered take differs");
    expect_probes_replayed(dir);
}

TEST(EngineTake, RefusesAFolderThatHoldsFiles) {
    const auto dir = test::temp_dir("engine-take-busy");
    std::ofstream(dir / "keep.txt") << "mine";
    EngineSession engine;
    ASSERT_TRUE(engine.start("models/bowed-string-220.json"));
    const auto started = engine.link().start_take(dir.string());
    ASSERT_TRUE(engine.await(StatusKind::Error,
                             [&](const StatusFrame& f) { return f.sequence == started; }));
    EXPECT_NE(engine.errors().back().find("already holds files"), std::string::npos)
        << engine.errors().back();
    EXPECT_EQ(test::read_file(dir / "keep.txt"), "mine");
}

TEST(EngineTake, ANewModelEndsTheTake) {
    const auto dir = test::temp_dir("engine-take-swap");
    EngineSession engine;
    ASSERT_TRUE(engine.start("models/bowed-string-220.json"));
    engine.link().start_take((dir / "take").string());
    engine.bow(0.3);
    engine.link().load_model(test::resource("models/bowed-string-440.json").string());
    std::string said;
    ASSERT_TRUE(engine.await_take_written(&said)) << said;
    expect_replayed(dir, "what was recorded before the swap still replays exactly");
}

// Killed outright, the engine finishes nothing: `render --take` recovers what it recorded.
TEST(EngineTake, AKilledEnginesTakeIsRecoveredByRender) {
    const auto dir = test::temp_dir("engine-take-kill");
    EngineSession engine;
    ASSERT_TRUE(engine.start("models/bowed-string-220.json"));
    engine.bow(0.3);
    engine.link().start_take((dir / "take").string());
    ASSERT_TRUE(engine.bow_until([&] {
        return size_of(dir / "take" / "take.wav") > 48000 * 3 / 2;
    })) << "the take never grew";
    // A change made while it records: streamed, and replayed by the recovered take.
    engine.link().send_parameter({"friction", "mu_s"}, 0.7);
    const std::uintmax_t before = size_of(dir / "take" / "take.wav");
    ASSERT_TRUE(engine.bow_until(
        [&] { return size_of(dir / "take" / "take.wav") > before + 48000 * 3 / 2; }));
    ::kill(engine.link().engine_pid(), SIGKILL);
    ASSERT_TRUE(wait_for([&] { return engine.link().liveness() == EngineLink::Liveness::Exited; },
                         kGenerous));
    const std::uintmax_t recorded = (size_of(dir / "take" / "take.wav") - 44) / 3;
    const auto r = test::run_archet(
        {"render", "--take", (dir / "take").string(), "-o", (dir / "again.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("interrupted"), std::string::npos) << r.err;
    const std::vector<int> original = samples_of(dir / "take" / "take.wav");
    EXPECT_EQ(original.size(), recorded) << "take.wav's header now counts all its samples";
    EXPECT_TRUE(samples_of(dir / "again.wav") == original)
        << "the recovered take reproduces what was recorded, from the state where it began";
    const TakeDescription take = read_take_file(dir / "take" / "take.json");
    EXPECT_TRUE(take.has_state && take.has_parameters && take.interrupted);
    EXPECT_FALSE(std::filesystem::exists(dir / "take" / "gesture.jsonl")) << "now gesture.json";
}

// SIGTERM (a logout, a service manager) ends the engine, but its take is finished first.
TEST(EngineTake, ASigtermedEngineFinishesItsTake) {
    const auto dir = test::temp_dir("engine-take-term");
    EngineSession engine;
    ASSERT_TRUE(engine.start("models/bowed-string-220.json"));
    engine.bow(0.3);
    engine.link().start_take((dir / "take").string());
    ASSERT_TRUE(engine.bow_until([&] { return size_of(dir / "take" / "take.wav") > 48000; }));
    ::kill(engine.link().engine_pid(), SIGTERM);
    ASSERT_TRUE(wait_for([&] { return engine.link().liveness() == EngineLink::Liveness::Exited; },
                         kGenerous));
    const nlohmann::json description = read_json(dir / "take" / "take.json");
    ASSERT_TRUE(description.is_object()) << "take.json is missing or damaged";
    EXPECT_EQ(description.value("complete", false), true);
    EXPECT_EQ(description.value("interrupted", false), true);
    EXPECT_EQ(description.value("interrupted_by", ""), "SIGTERM");
    expect_replayed(dir, "the interrupted take re-renders to the byte");
}

// A take that clips says so in take.json and in the message the studio shows, though the
// live limiter kept what was heard clean.
TEST(EngineTake, TheFinishedMessageSaysTheTakeClipped) {
    const auto dir = test::temp_dir("engine-take-clip");
    EngineSession engine;
    ASSERT_TRUE(engine.start("models/bowed-string-220.json"));
    engine.link().start_take((dir / "take").string());
    engine.bow(0.6, 0.1);
    engine.link().stop_take();
    std::string said;
    ASSERT_TRUE(engine.await_take_written(&said)) << said;
    EXPECT_NE(said.find("clipped"), std::string::npos) << said;
    EXPECT_NE(said.find("output_gain"), std::string::npos) << said;
    const nlohmann::json description = read_json(dir / "take" / "take.json");
    ASSERT_TRUE(description.is_object());
    EXPECT_GT(description.value("clipped_samples", 0.0), 100.0) << description.dump();
    EXPECT_GE(description.value("peak", 0.0), 1.0);
}

}  // namespace
}  // namespace archet::ipc
