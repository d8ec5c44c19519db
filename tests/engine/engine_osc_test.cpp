// OSC into a real engine process: a program on this machine (here liblo, as Max, Pd or
// SuperCollider would) bows the string, stops it with the finger and records a take that
// re-renders to the byte; malformed and unknown messages are refused with a sentence and
// change nothing; thousands of messages cost the real-time thread no allocation.

#include <gtest/gtest.h>
#include <lo/lo.h>
#include <netinet/in.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "archet/builders/bowed_string.hpp"
#include "archet/files/model_file.hpp"
#include "archet/files/take_file.hpp"
#include "engine_session.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

using ipc::StatusFrame;
using ipc::StatusKind;
using test::EngineSession;

// A UDP port free on the loopback now (the kernel's pick).
int free_udp_port() {
    const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a);
    socklen_t size = sizeof a;
    ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &size);
    ::close(s);
    return ntohs(a.sin_port);
}

struct OscEngine {
    OscEngine() : port(free_udp_port()), engine(with_osc(port)) {
        to = lo_address_new("127.0.0.1", std::to_string(port).c_str());
    }
    ~OscEngine() { lo_address_free(to); }
    static EngineSession::EngineLinkOptions with_osc(int port) {
        auto o = EngineSession::options();
        o.osc_port = port;
        return o;
    }
    // The fingered paper string at 220 Hz, built here.
    bool start(const std::filesystem::path& dir) {
        BowedStringOptions o;
        o.pitch = 220, o.paper = true, o.finger = true;
        write_file_atomically(dir / "fingered.json", format_model(build_bowed_string(o)));
        return engine.start_file(dir / "fingered.json");
    }
    // Bows from OSC for `seconds` of sound: pressed in, sliding at 0.05 m/s.
    bool bow(double seconds) {
        const auto until = engine.played() + static_cast<std::uint64_t>(seconds * 48000);
        return engine.play_until([&] { return engine.played() >= until; },
                                 [&](double t) {
                                     lo_send(to, "/archet/bow/press", "f", 0.0015f);
                                     lo_send(to, "/archet/bow/slide", "f",
                                             static_cast<float>(-0.05 + 0.05 * t));
                                 });
    }
    // Waits for the engine's refusal of the message just sent.
    std::string refusal() {
        const std::size_t before = engine.errors().size();
        engine.await(StatusKind::Error, [](const StatusFrame&) { return true; });
        return engine.errors().size() > before ? engine.errors().back() : "";
    }

    int port;
    EngineSession engine;
    lo_address to;
};

TEST(EngineOsc, BowsStopsWithTheFingerAndRecordsATakeThatReRendersToTheByte) {
    const auto dir = test::temp_dir("engine-osc");
    OscEngine osc;
    ASSERT_TRUE(osc.start(dir));
    ASSERT_TRUE(osc.bow(0.5));
    EXPECT_GT(osc.engine.latest().values[4], 0.01) << "the bow is pressed in from OSC";
    EXPECT_NE(osc.engine.latest().values[2], 0.0) << "and slides (bow_v)";
    lo_send(osc.to, "/archet/record", "s", "start");
    std::string folder;
    ASSERT_TRUE(osc.engine.await(StatusKind::Take, [&](const StatusFrame& f) {
        folder = f.text;
        return folder.rfind("recording ", 0) == 0;
    })) << (osc.engine.errors().empty() ? "" : osc.engine.errors().back());
    folder = folder.substr(std::string("recording ").size());
    ASSERT_TRUE(osc.bow(0.3));
    lo_send(osc.to, "/archet/finger", "f", 2.0f / 3.0f);
    ASSERT_TRUE(osc.bow(0.3));
    lo_send(osc.to, "/archet/record", "s", "stop");
    std::string said;
    ASSERT_TRUE(osc.engine.await_take_written(&said)) << said;
    EXPECT_TRUE(osc.engine.errors().empty()) << osc.engine.errors().front();

    const auto changes = read_parameter_changes(std::filesystem::path(folder) / "parameters.json");
    ASSERT_EQ(changes.size(), 1u);
    EXPECT_EQ(changes[0].parameter, "finger.position");
    EXPECT_DOUBLE_EQ(changes[0].value, static_cast<double>(2.0f / 3.0f));
    const auto r =
        test::run_archet({"render", "--take", folder, "-o", (dir / "again.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(test::read_file(dir / "again.wav"),
              test::read_file(std::filesystem::path(folder) / "take.wav"))
        << "the take made from OSC re-renders to the byte";
    std::filesystem::remove_all(folder);
}

// A fader that never rests (vibrato, a slowly turned knob) keeps a parameter gliding: a take
// asked for then begins at once, the glide in flight carried into it, and re-renders to the
// byte.
TEST(EngineOsc, ATakeBeginsWhileAFaderStreamsAndReRendersToTheByte) {
    const auto dir = test::temp_dir("engine-osc-stream");
    OscEngine osc;
    ASSERT_TRUE(osc.start(dir));
    double t = 0;
    auto stream = [&](double) {
        lo_send(osc.to, "/archet/bow/press", "f", 0.0015f);
        lo_send(osc.to, "/archet/bow/slide", "f", static_cast<float>(-0.05 + 0.05 * t));
        lo_send(osc.to, "/archet/finger", "f", static_cast<float>(0.8 + 0.05 * std::sin(30 * t)));
        t += 0.002;
    };
    const auto warm = osc.engine.played() + 9600;
    ASSERT_TRUE(osc.engine.play_until([&] { return osc.engine.played() >= warm; }, stream));
    const auto folder = dir / "take";
    osc.engine.link().start_take(folder.string());
    ASSERT_TRUE(osc.engine.play_until(
        [&] {
            return osc.engine.seen(StatusKind::Take, [](const StatusFrame& s) {
                return std::string(s.text).rfind("recording ", 0) == 0;
            });
        },
        stream))
        << "the take never began while the finger glided";
    const auto until = osc.engine.played() + 14400;
    ASSERT_TRUE(osc.engine.play_until([&] { return osc.engine.played() >= until; }, stream));
    osc.engine.link().stop_take();
    std::string said;
    ASSERT_TRUE(osc.engine.await_take_written(&said)) << said;
    const auto changes = read_parameter_changes(folder / "parameters.json");
    ASSERT_FALSE(changes.empty()) << "the finger moved during the take";
    const auto r =
        test::run_archet({"render", "--take", folder.string(), "-o", (dir / "again.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(test::read_file(dir / "again.wav"), test::read_file(folder / "take.wav"))
        << "re-rendered to the byte, the glides included";
}

// /archet/param bow.position moves the bow as the studio's inspector does: the take keeps the
// move, and re-renders to the byte.
TEST(EngineOsc, MovesTheBowAlongTheStringWhileItPlays) {
    const auto dir = test::temp_dir("engine-osc-bow");
    OscEngine osc;
    ASSERT_TRUE(osc.start(dir));
    ASSERT_TRUE(osc.bow(0.3));
    const auto folder = dir / "take";
    osc.engine.link().start_take(folder.string());
    ASSERT_TRUE(osc.engine.await(StatusKind::Take, [](const StatusFrame& f) {
        return std::string(f.text).rfind("recording ", 0) == 0;
    }));
    ASSERT_TRUE(osc.bow(0.2));
    lo_send(osc.to, "/archet/param", "sf", "bow.position", 0.25f);
    ASSERT_TRUE(osc.bow(0.3));
    EXPECT_GT(osc.engine.latest().values[4], 0.01) << "still pressed in";
    osc.engine.link().stop_take();
    std::string said;
    ASSERT_TRUE(osc.engine.await_take_written(&said)) << said;
    EXPECT_TRUE(osc.engine.errors().empty()) << osc.engine.errors().front();
    const auto changes = read_parameter_changes(folder / "parameters.json");
    ASSERT_EQ(changes.size(), 1u);
    EXPECT_EQ(changes[0].parameter, "bow.position");
    EXPECT_DOUBLE_EQ(changes[0].value, static_cast<double>(0.25f));
    const auto r =
        test::run_archet({"render", "--take", folder.string(), "-o", (dir / "again.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(test::read_file(dir / "again.wav"), test::read_file(folder / "take.wav"));
}

TEST(EngineOsc, RefusesWhatItCannotActOnAndSaysWhy) {
    const auto dir = test::temp_dir("engine-osc-bad");
    OscEngine osc;
    ASSERT_TRUE(osc.start(dir));
    lo_send(osc.to, "/archet/nothing", "f", 1.0f);
    EXPECT_NE(osc.refusal().find("unknown address \"/archet/nothing\""), std::string::npos);
    lo_send(osc.to, "/archet/finger", "s", "high");
    EXPECT_NE(osc.refusal().find("takes one number"), std::string::npos);
    lo_send(osc.to, "/archet/finger", "f", 1.5f);
    EXPECT_NE(osc.refusal().find("out of range"), std::string::npos);
    lo_send(osc.to, "/archet/param", "sf", "friction.mu_s", 50.0f);
    const std::string mu = osc.refusal();
    EXPECT_NE(mu.find("friction.mu_s: must be at most 10"), std::string::npos) << mu;
    lo_send(osc.to, "/archet/param", "sf", "nobody.mass", 1.0f);
    EXPECT_NE(osc.refusal().find("nobody"), std::string::npos);
    // Bytes that are not OSC at all.
    const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET, a.sin_port = htons(static_cast<std::uint16_t>(osc.port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    const char junk[] = "not an OSC message at all";
    ::sendto(s, junk, sizeof junk, 0, reinterpret_cast<sockaddr*>(&a), sizeof a);
    ::close(s);
    EXPECT_NE(osc.refusal().find("malformed"), std::string::npos);
    // Still playing, the model as it was.
    ASSERT_TRUE(osc.bow(0.2));
    EXPECT_GT(osc.engine.latest().values[4], 0.01);
}

TEST(EngineOsc, ThousandsOfMessagesCostTheRealTimeThreadNoAllocation) {
    const auto dir = test::temp_dir("engine-osc-flood");
    OscEngine osc;
    ASSERT_TRUE(osc.start(dir));
    for (int i = 0; i < 5000; ++i) {
        lo_send(osc.to, "/archet/bow/slide", "f", static_cast<float>(0.0001 * (i % 100)));
        if (i % 50 == 0) lo_send(osc.to, "/archet/finger", "f", 0.5f + 0.001f * (i % 200));
        if (i % 100 == 0) lo_send(osc.to, "/archet/param", "sf", "friction.mu_s", 0.75f);
    }
    ASSERT_TRUE(osc.bow(0.5));
    ASSERT_TRUE(osc.engine.await(StatusKind::Heartbeat, [](const StatusFrame&) { return true; }));
    EXPECT_EQ(osc.engine.realtime_allocations(), 0u);
    EXPECT_TRUE(osc.engine.errors().empty()) << osc.engine.errors().front();
}

// OSC moves one axis from where the pad left both: a sender of the slide alone keeps the
// pad's press, and the bow stays on the string.
TEST(EngineOsc, OneAxisFromOscKeepsThePadsOther) {
    const auto dir = test::temp_dir("engine-osc-axis");
    OscEngine osc;
    ASSERT_TRUE(osc.start(dir));
    osc.engine.bow(0.3, 0.0015);  // the pad presses the bow in
    const auto until = osc.engine.played() + 24000;
    ASSERT_TRUE(osc.engine.play_until([&] { return osc.engine.played() >= until; },
                                      [&](double t) {
                                          lo_send(osc.to, "/archet/bow/slide", "f",
                                                  static_cast<float>(0.05 * t));
                                      }));
    EXPECT_GT(osc.engine.latest().values[4], 0.01) << "still pressed: the pad's press was kept";
    EXPECT_TRUE(osc.engine.errors().empty()) << osc.engine.errors().front();
}

// With --osc-send the engine tells a visualiser what the bow does: the bow force and the
// string's energy, about 20 times a second, as they are (positive when bowed).
TEST(EngineOsc, SendsTheBowForceAndTheEnergyToAVisualiser) {
    struct Heard {
        double bow_force = -1, energy = -1;
        int messages = 0;
    } heard;
    lo_server visualiser = lo_server_new_with_proto(nullptr, LO_UDP, nullptr);
    ASSERT_NE(visualiser, nullptr);
    auto hear = [](const char* path, const char*, lo_arg** argv, int, lo_message, void* data) {
        auto& h = *static_cast<Heard*>(data);
        (std::string(path) == "/archet/out/bow_force" ? h.bow_force : h.energy) = argv[0]->f;
        ++h.messages;
        return 0;
    };
    lo_server_add_method(visualiser, "/archet/out/bow_force", "f", hear, &heard);
    lo_server_add_method(visualiser, "/archet/out/energy", "f", hear, &heard);
    auto o = OscEngine::with_osc(free_udp_port());
    o.osc_send = "127.0.0.1:" + std::to_string(lo_server_get_port(visualiser));
    EngineSession engine(o);
    ASSERT_TRUE(engine.start("models/bowed-string-220.json"));
    engine.bow(0.5);
    EXPECT_TRUE(test::wait_for(
        [&] {
            engine.bow(0.05);
            while (lo_server_recv_noblock(visualiser, 0) > 0) {
            }
            return heard.bow_force > 0.01 && heard.energy > 0;
        },
        test::kGenerous))
        << heard.messages << " messages, bow force " << heard.bow_force;
    lo_server_free(visualiser);
}

// A port another program holds costs the engine its OSC, not its sound: it says so and plays.
// `archet play --osc` without the studio: a sender bows the model through the engine it starts,
// and the take it records re-renders to the byte.
TEST(EngineOsc, PlayFromTheCommandLineRecordsWhatOscPlays) {
    const auto dir = test::temp_dir("play-osc");
    BowedStringOptions o;
    o.pitch = 220, o.paper = true, o.finger = true;
    write_file_atomically(dir / "fingered.json", format_model(build_bowed_string(o)));
    const int port = free_udp_port();
    const auto take = dir / "take";
    std::vector<std::string> args{ARCHET_BINARY,
                                  "play",
                                  (dir / "fingered.json").string(),
                                  "--osc",
                                  std::to_string(port),
                                  "--take",
                                  take.string(),
                                  "--duration",
                                  "3"};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = -1;
    ASSERT_EQ(::posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ), 0);
    ASSERT_TRUE(test::wait_for([&] { return std::filesystem::exists(take / "take.wav"); },
                               test::kGenerous));
    lo_address to = lo_address_new("127.0.0.1", std::to_string(port).c_str());
    int status = -1;
    for (int i = 0; ::waitpid(pid, &status, WNOHANG) == 0; ++i) {  // until play's duration ends
        lo_send(to, "/archet/bow/press", "f", 0.0015f);
        lo_send(to, "/archet/bow/slide", "f", static_cast<float>(0.0002 * i));
        ::usleep(2000);
    }
    lo_address_free(to);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
    const auto r =
        test::run_archet({"render", "--take", take.string(), "-o", (dir / "again.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(test::read_file(dir / "again.wav"), test::read_file(take / "take.wav"));
    // OSC pressed the bow in: the take's normal force rose.
    const std::vector<double> normal = test::probe_column(take / "probes.csv", "normal_force");
    ASSERT_FALSE(normal.empty());
    EXPECT_GT(*std::max_element(normal.begin(), normal.end()), 0.05) << "OSC pressed the bow in";
}

TEST(EngineOsc, APortAlreadyTakenIsSaidAndTheEnginePlaysOn) {
    const int holder = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET, a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(::bind(holder, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    socklen_t size = sizeof a;
    ::getsockname(holder, reinterpret_cast<sockaddr*>(&a), &size);
    auto o = EngineSession::options();
    o.osc_port = ntohs(a.sin_port);
    EngineSession engine(o);
    engine.link().start();
    std::string said;
    EXPECT_TRUE(engine.await(StatusKind::Heartbeat, [&](const StatusFrame& f) {
        said = f.text;
        return said.find("no OSC") != std::string::npos;
    })) << said;
    EXPECT_NE(said.find("pick another port"), std::string::npos) << said;
    const auto loaded =
        engine.link().load_model(test::resource("models/bowed-string-220.json").string());
    EXPECT_TRUE(engine.await(StatusKind::ModelLoaded,
                             [&](const StatusFrame& f) { return f.sequence == loaded; }));
    ::close(holder);
}

}  // namespace
}  // namespace archet
