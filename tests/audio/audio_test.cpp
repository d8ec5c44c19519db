// Live audio: `archet play` on the null sink, and on a real JACK server running its dummy
// driver at 64-frame buffers for a minute with no xrun. Skips itself where jackd is missing; where
// the machine itself stalled while archet played (deadline_witness.hpp), it holds archet to no
// more missed deadlines than the machine's stalls, and then skips rather than ask for zero.

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <nlohmann/json.hpp>
#include <thread>

#include "deadline_witness.hpp"
#include "jack_dummy.hpp"
#include "test_support.hpp"

extern char** environ;

namespace archet {
namespace {

nlohmann::json last_json_line(const std::string& out) {
    const auto start = out.rfind('{');
    return nlohmann::json::parse(out.substr(start));
}

constexpr std::chrono::nanoseconds kPeriodOf64Frames{1'000'000'000LL * 64 / 48000};
/// The shipped strings' gesture link ticks at 3 kHz: 4 ticks a block of 64 frames at 48 kHz.
constexpr std::uint64_t kHapticTicksPerBlock = 64 * 3000 / 48000;

// How many xruns one stall of the machine may be reported as. The null sink counts a late
// block once. JACK may tell its clients of one stall twice: its dummy driver reports the cycle
// it started late (JackTimedDriver::ProcessWait), and the engine each client that had not
// finished by then (JackEngine::CheckXRun); RtAudio counts both when a block falls between
// them. The stalls are counted once however many CPUs saw them (missed_by_the_machine()).
constexpr int kNullSinkXrunsPerStall = 1;
constexpr int kJackXrunsPerStall = 2;

// Xruns, late blocks and a block that took longer than it lasts are archet's only when the
// machine itself kept the same deadlines. When it did not, each of archet's missed deadlines
// needs one of the machine's: more than that is still archet's. Called last: it may skip.
void expect_every_deadline_kept(const nlohmann::json& stats, const test::DeadlineWitness& machine,
                                int haptic_ticks_per_block, int xruns_per_stall) {
    const auto xruns = stats["xruns"].get<std::uint64_t>();
    const auto late_blocks = stats["haptic_late_ticks"].get<std::uint64_t>() /
                             static_cast<std::uint64_t>(haptic_ticks_per_block);
    const bool slow_block =
        stats["worst_callback_us"].get<double>() >= stats["callback_budget_us"].get<double>();
    ::testing::Test::RecordProperty("xruns", static_cast<int>(xruns));
    ::testing::Test::RecordProperty("machine_missed_deadlines", static_cast<int>(machine.missed()));
    const std::string figures = stats.dump() + "; " + machine.describe();
    if (machine.missed() > 0) {
        EXPECT_LE(xruns,
                  machine.missed_by_the_machine() * static_cast<std::uint64_t>(xruns_per_stall))
            << "more xruns than the machine's own stalls can explain: " << figures;
        EXPECT_LE(late_blocks, machine.missed())
            << "more late blocks than the machine's own stalls: " << figures;
        if (xruns > 0 || late_blocks > 0 || slow_block)
            GTEST_SKIP() << "zero xruns cannot be asked here, only as many as the machine's own "
                            "stalls (a virtual machine whose host takes its CPUs away; run on one "
                            "that keeps real-time deadlines): "
                         << figures;
    }
    EXPECT_EQ(xruns, 0u) << figures;
    EXPECT_EQ(late_blocks, 0u) << figures;
    EXPECT_FALSE(slow_block) << figures;
}

// A 64-frame block every period of the duration, give or take `start_and_stop` blocks. A block
// late by a whole period or more is dropped, as a device would have (the null sink does so, and
// JACK's dummy driver skips the cycles it missed): a stall of the machine drops one for each
// period it missed (a 100 ms stall, 75), and only those.
void expect_a_block_every_period(const nlohmann::json& stats, double seconds,
                                 const test::DeadlineWitness& machine, double start_and_stop) {
    const double blocks = seconds * 48000 / 64;
    const auto callbacks = stats["callbacks"].get<double>();
    EXPECT_LE(callbacks, blocks + start_and_stop) << stats.dump();
    EXPECT_GE(callbacks,
              blocks - start_and_stop - static_cast<double>(machine.missed_by_the_machine()))
        << stats.dump() << "; " << machine.describe();
}

// Blocks the null sink may play more or fewer than the duration's: its start and stop.
constexpr double kNullSinkStartAndStop = 60;
// JACK's: the client joins the server's graph and leaves it, up to a second.
constexpr double kJackStartAndStop = 750;

// The witness is only as good as the stalls it sees. A child process stops this one (all its
// threads, as a host taking the CPUs away does) for longer than half a period, at every phase
// of the witness's period, and the witness must count each stall: once a period, it saw a third
// of them. (A shell running the test by hand reports the stops; ctest does not.)
TEST(DeadlineWitness, CountsEveryStallLongerThanHalfAPeriod) {
    constexpr int kStalls = 24;
    constexpr std::chrono::nanoseconds kStall = kPeriodOf64Frames * 3 / 4;
    test::DeadlineWitness machine(kPeriodOf64Frames);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // the witness is waking
    const pid_t self = ::getpid();
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        // Only async-signal-safe calls after a fork from threads.
        for (int i = 0; i < kStalls; ++i) {
            // Three periods apart and a 24th of a period more each time: the stalls begin at
            // every phase of the witness's wake-ups.
            const timespec apart{0, static_cast<long>(kPeriodOf64Frames.count() * (3 + i / 24.0))};
            ::nanosleep(&apart, nullptr);
            ::kill(self, SIGSTOP);
            const timespec stall{0, static_cast<long>(kStall.count())};
            ::nanosleep(&stall, nullptr);
            ::kill(self, SIGCONT);
        }
        ::_exit(0);
    }
    int status = 0;
    while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    machine.stop();
    ASSERT_TRUE(WIFEXITED(status));
    if (!machine.realtime()) GTEST_SKIP() << "no SCHED_FIFO here: " << machine.describe();
    // The witness of each CPU sees each stall; it may also see the machine's own.
    EXPECT_GE(machine.missed(), static_cast<std::uint64_t>(kStalls) * machine.cpus())
        << machine.describe();
    // The whole process stopped: every CPU's thread saw the same stalls, which count once
    // merged (and short ones once each: three quarters of a period is less than one).
    EXPECT_GE(machine.missed_by_the_machine(), static_cast<std::uint64_t>(kStalls))
        << machine.describe();
    EXPECT_LE(machine.missed_by_the_machine(), machine.missed()) << machine.describe();
}

TEST(Audio, PlaysIntoTheNullSinkInRealTimeWithoutAllocating) {
    test::DeadlineWitness machine(kPeriodOf64Frames);
    const auto r =
        test::run_archet({"play", test::resource("models/bowed-string-220.json").string(),
                          "--audio", "null", "--duration", "1.5", "--stats"});
    machine.stop();
    ASSERT_EQ(r.status, 0) << r.err;
    const auto s = last_json_line(r.out);
    expect_a_block_every_period(s, 1.5, machine, kNullSinkStartAndStop);
    EXPECT_EQ(s["realtime_allocations"].get<int>(), 0);
    EXPECT_EQ(s["haptic_ticks"].get<std::uint64_t>(),
              kHapticTicksPerBlock * s["callbacks"].get<std::uint64_t>())
        << "the gesture link at 3 kHz, 4 ticks a block";
    EXPECT_NE(r.err.find("real-time scheduling"), std::string::npos)
        << "says whether it got it: " << r.err;
    for (const char* key : {"callbacks", "xruns", "worst_callback_us", "callback_budget_us",
                            "haptic_ticks", "haptic_late_ticks"})
        ASSERT_TRUE(s.contains(key)) << key;
    expect_every_deadline_kept(s, machine, kHapticTicksPerBlock, kNullSinkXrunsPerStall);
}

TEST(Audio, AnUnknownApiIsRefusedAndAMissingDeviceFallsBackToTheNullSink) {
    auto r = test::run_archet(
        {"play", test::resource("models/bowed-string-220.json").string(), "--audio", "oss"});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("use jack, alsa, pulse, auto or null"), std::string::npos) << r.err;
    ::setenv("JACK_DEFAULT_SERVER", "archet-no-such-server", 1);
    r = test::run_archet({"play", test::resource("models/bowed-string-220.json").string(),
                          "--audio", "jack", "--duration", "0.3", "--stats"});
    ::unsetenv("JACK_DEFAULT_SERVER");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("playing into a null sink instead"), std::string::npos) << r.err;
    EXPECT_NE(last_json_line(r.out)["output"].get<std::string>().find("null sink"),
              std::string::npos);
    // auto takes the first output that opens, and says so when none does.
    ::setenv("JACK_DEFAULT_SERVER", "archet-no-such-server", 1);
    r = test::run_archet({"play", test::resource("models/bowed-string-220.json").string(),
                          "--audio", "auto", "--duration", "0.3", "--stats"});
    ::unsetenv("JACK_DEFAULT_SERVER");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string output = last_json_line(r.out)["output"].get<std::string>();
    if (output.find("null sink") != std::string::npos) {
        EXPECT_NE(r.err.find("no audio output opened (jack: "), std::string::npos) << r.err;
    }
}

TEST(Audio, PlaysThroughTheSimulatedHapticDevice) {
    test::DeadlineWitness machine(kPeriodOf64Frames);
    const auto r =
        test::run_archet({"play", test::resource("models/bowed-string-220.json").string(),
                          "--audio", "null", "--haptic", "sim", "--duration", "1", "--stats"});
    machine.stop();
    ASSERT_EQ(r.status, 0) << r.err;
    const auto s = last_json_line(r.out);
    expect_a_block_every_period(s, 1.0, machine, kNullSinkStartAndStop);
    EXPECT_EQ(s["haptic_ticks"].get<std::uint64_t>(),
              kHapticTicksPerBlock * s["callbacks"].get<std::uint64_t>())
        << "the gesture link at 3 kHz, 4 ticks a block";
    EXPECT_EQ(s["realtime_allocations"].get<int>(), 0)
        << "hand, link and model in the callback, allocation-free";
    const std::string model = test::resource("models/bowed-string-220.json").string();
    for (const auto& [device, expected] : std::vector<std::pair<std::string, std::string>>{
             {"evdev:/dev/input/no-such-joystick", "cannot open the device"},
             {"evdev:/dev/null", "not an input device"},
             {"joystick", "is not a haptic device; use none, sim, evdev:"},
             {"sdl:99", "there is no joystick 99"}}) {
        const auto bad = test::run_archet({"play", model, "--haptic", device, "--duration", "0.2"});
        EXPECT_EQ(bad.status, 2) << device;
        EXPECT_NE(bad.err.find(expected), std::string::npos) << bad.err;
    }
    const auto devices = test::run_archet({"devices"});
    EXPECT_EQ(devices.status, 0);
    EXPECT_NE(devices.out.find("sim: simulated hand"), std::string::npos) << devices.out;
}

using JackServer = test::JackDummy;

TEST_F(JackServer, TheFullBandwidth110HzStringAt64FramesForAMinuteWithoutXruns) {
    test::DeadlineWitness machine(kPeriodOf64Frames);
    const auto r =
        test::run_archet({"play", test::resource("models/bowed-string-110.json").string(),
                          "--audio", "jack", "--buffer", "64", "--duration", "60", "--gesture",
                          test::resource("gestures/detache.json").string(), "--stats"});
    machine.stop();
    ASSERT_EQ(r.status, 0) << r.err;
    const auto s = last_json_line(r.out);
    EXPECT_NE(s["output"].get<std::string>().find("jack"), std::string::npos) << r.err;
    expect_a_block_every_period(s, 60, machine, kJackStartAndStop);
    EXPECT_EQ(s["realtime_allocations"].get<int>(), 0);
    expect_every_deadline_kept(s, machine, kHapticTicksPerBlock, kJackXrunsPerStall);
}

}  // namespace
}  // namespace archet
