// Live takes: re-rendering a take's gesture reproduces its audio to the byte; killing the
// player mid-take still leaves a valid WAV up to the last second; a take never writes into a
// folder that holds files.

#include <gtest/gtest.h>
#include <signal.h>
#include <sndfile.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <thread>

#include "test_support.hpp"

extern char** environ;

namespace archet {
namespace {

sf_count_t frames_of(const std::filesystem::path& wav) {
    SF_INFO info{};
    SNDFILE* f = sf_open(wav.c_str(), SFM_READ, &info);
    if (!f) return -1;
    sf_close(f);
    return info.frames;
}

void expect_reproduced(const std::vector<std::string>& play_extra, const std::string& name) {
    const auto dir = test::temp_dir(name);
    const std::string model = test::resource("models/bowed-string-220.json").string();
    std::vector<std::string> play{"play", model,    "--duration",
                                  "1",    "--take", (dir / "take").string()};
    play.insert(play.end(), play_extra.begin(), play_extra.end());
    auto r = test::run_archet(play);
    ASSERT_EQ(r.status, 0) << r.err;
    const sf_count_t frames = frames_of(dir / "take" / "take.wav");
    // Sound: how much of the wall-clock second was played is the machine's speed (a machine
    // that stalls, or runs under a sanitizer, loses whole blocks, which the take never had).
    ASSERT_GT(frames, 0);
    std::ostringstream duration;
    duration << std::setprecision(17) << static_cast<double>(frames) / 48000.0;
    r = test::run_archet({"render", model, "--gesture", (dir / "take" / "gesture.json").string(),
                          "--duration", duration.str(), "-o", (dir / "again.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(test::read_file(dir / "again.wav"), test::read_file(dir / "take" / "take.wav"))
        << "the re-rendered take differs";
    // And in one command, from the take's own description.
    r = test::run_archet(
        {"render", "--take", (dir / "take").string(), "-o", (dir / "replayed.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(test::read_file(dir / "replayed.wav"), test::read_file(dir / "take" / "take.wav"))
        << "render --take differs";
    // And it was a real take: bowed, with probes for every sample.
    const std::string csv = test::read_file(dir / "take" / "probes.csv");
    EXPECT_EQ(static_cast<sf_count_t>(std::count(csv.begin(), csv.end(), '\n')), frames + 1);
}

TEST(Take, WithTheSimulatedHandReRendersToTheByte) {
    expect_reproduced({"--haptic", "sim"}, "take-hand");
}

TEST(Take, FromAGestureFileReRendersToTheByte) {
    expect_reproduced({"--gesture", test::resource("gestures/detache.json").string()}, "take-file");
}

TEST(Take, AKilledPlayerLeavesAValidWavUpToTheLastSecond) {
    const auto dir = test::temp_dir("take-crash");
    std::vector<std::string> args{
        ARCHET_BINARY,          "play", test::resource("models/bowed-string-220.json").string(),
        "--duration",           "20",   "--take",
        (dir / "take").string()};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = -1;
    ASSERT_EQ(::posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ), 0);
    // Until the WAV's header (updated once a second) holds two seconds of sound, however
    // slowly the machine plays: waited for, not assumed after a wall-clock time.
    const bool two_seconds =
        test::wait_for([&] { return frames_of(dir / "take" / "take.wav") >= 2 * 48000; },
                       std::chrono::milliseconds(120000));
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    ASSERT_TRUE(two_seconds) << "the take's header never said two seconds";
    const sf_count_t frames = frames_of(dir / "take" / "take.wav");
    EXPECT_GE(frames, 2 * 48000) << "at least the seconds before the last header update";
    EXPECT_LE(frames, 20 * 48000) << "no more than was played";
}

TEST(Take, NeverWritesIntoAFolderThatHoldsFiles) {
    const auto dir = test::temp_dir("take-busy");
    { std::ofstream(dir / "mine.txt") << "the user's notes"; }
    const auto r =
        test::run_archet({"play", test::resource("models/bowed-string-220.json").string(),
                          "--duration", "0.2", "--take", dir.string()});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("already holds files"), std::string::npos) << r.err;
    EXPECT_EQ(test::read_file(dir / "mine.txt"), "the user's notes");
}

TEST(Take, ADamagedTakeIsRefusedByNameAndKept) {
    const auto dir = test::temp_dir("take-damaged");
    auto r = test::run_archet({"play", test::resource("models/bowed-string-220.json").string(),
                               "--duration", "0.3", "--take", (dir / "take").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string take = (dir / "take").string();
    const std::string description = test::read_file(dir / "take" / "take.json");
    auto expect_refused = [&](const std::string& expected) {
        const auto bad = test::run_archet({"render", "--take", take, "-o", take + "/x.wav"});
        EXPECT_EQ(bad.status, 2) << bad.err;
        EXPECT_NE(bad.err.find(expected), std::string::npos) << bad.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "take" / "x.wav"));
    };
    // It says it began mid-performance, but its state is missing, foreign or cut short.
    std::string with_state = description;
    with_state.replace(with_state.find("\"state\": false"), 14, "\"state\": true");
    std::ofstream(dir / "take" / "take.json") << with_state;
    expect_refused("state.bin: cannot open the state file");
    std::ofstream(dir / "take" / "state.bin") << "RIFF....WAVE";
    expect_refused("is not an Archet state file");
    std::ofstream(dir / "take" / "state.bin") << "archet-state 1 3\n" << std::string(24, '\0');
    expect_refused("holds 3 numbers but model.json needs");
    std::ofstream(dir / "take" / "state.bin") << "archet-state 1 3\n" << std::string(10, '\0');
    expect_refused("is truncated or damaged");
    std::ofstream(dir / "take" / "take.json") << "{\"format\": \"archet-take\", \"version\": 1}";
    expect_refused("sample_rate");
    r = test::run_archet({"render", "--take", take,
                          test::resource("models/bowed-string-220.json").string(), "-o",
                          take + "/x.wav"});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("replays the take as it was played"), std::string::npos) << r.err;
    EXPECT_GT(test::read_file(dir / "take" / "take.wav").size(), 10000u) << "the take is kept";
}

}  // namespace
}  // namespace archet
