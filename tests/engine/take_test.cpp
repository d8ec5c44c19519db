// Live takes: re-rendering a take's gesture reproduces its audio to the byte; SIGINT, SIGTERM
// and SIGHUP finish the take cleanly; a take killed outright is recovered by `render --take`;
// a take that clips says so; a take never writes into a folder that holds files; a take of an
// older scheme revision says it matches only up to rounding.

#include <gtest/gtest.h>
#include <signal.h>
#include <sndfile.h>
#include <spawn.h>
#include <sys/wait.h>

#include <fcntl.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "archet/builders/bowed_string.hpp"
#include "archet/common/input_error.hpp"
#include "archet/common/input_limits.hpp"
#include "archet/common/scheme_revision.hpp"
#include "archet/engine/take_recorder.hpp"
#include "archet/files/take_file.hpp"
#include "archet/files/take_recovery.hpp"
#include "archet/physics/parameter_smoother.hpp"
#include "archet/physics/simulation.hpp"
#include "take_file_support.hpp"
#include "test_support.hpp"

extern char** environ;

namespace archet {
namespace {

using test::read_json;
using test::samples_of;
using test::size_of;

sf_count_t frames_of(const std::filesystem::path& wav) {
    SF_INFO info{};
    SNDFILE* f = sf_open(wav.c_str(), SFM_READ, &info);
    if (!f) return -1;
    sf_close(f);
    return info.frames;
}

// Whether two files hold the same bytes; where not, their sizes and where they first differ
// (GoogleTest's difference of two long texts takes memory in the product of their lengths).
::testing::AssertionResult same_bytes(const std::filesystem::path& a,
                                      const std::filesystem::path& b) {
    const std::string x = test::read_file(a), y = test::read_file(b);
    if (x == y) return ::testing::AssertionSuccess();
    const auto at = static_cast<std::size_t>(
        std::mismatch(x.begin(), x.end(), y.begin(), y.end()).first - x.begin());
    const auto line = std::count(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(at), '\n');
    return ::testing::AssertionFailure()
           << a.filename() << " (" << x.size() << " bytes) and " << b.filename() << " (" << y.size()
           << " bytes) differ from byte " << at << " (line " << line + 1 << ")";
}

// Plays `played` (the shipped 220 Hz string by default) with a take into dir/take.
void expect_reproduced(const std::vector<std::string>& play_extra, const std::filesystem::path& dir,
                       const std::filesystem::path& played = {}) {
    const std::string model =
        (played.empty() ? test::resource("models/bowed-string-220.json") : played).string();
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
    EXPECT_TRUE(same_bytes(dir / "again.wav", dir / "take" / "take.wav"))
        << "the re-rendered take differs";
    // And in one command, from the take's own description, every probe too: `play` runs the
    // string in runs up to the hand's next tick (Simulation::run()), the re-render tick by tick.
    r = test::run_archet({"render", "--take", (dir / "take").string(), "-o",
                          (dir / "replayed.wav").string(), "--probes",
                          (dir / "replayed.csv").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(same_bytes(dir / "replayed.wav", dir / "take" / "take.wav"))
        << "render --take differs";
    EXPECT_TRUE(same_bytes(dir / "replayed.csv", dir / "take" / "probes.csv"))
        << "the take's probes re-render to the byte, times included";
    EXPECT_EQ(read_json(dir / "take" / "take.json")["scheme"], kSchemeRevision);
    EXPECT_FALSE(read_json(dir / "take" / "take.json").contains("dropped_samples"))
        << "a take that lost nothing reads in an Archet that knows no losses";
    EXPECT_EQ(r.err.find("scheme revision"), std::string::npos) << r.err;
    // And it was a real take: bowed, with probes for every sample.
    const std::string csv = test::read_file(dir / "take" / "probes.csv");
    EXPECT_EQ(static_cast<sf_count_t>(std::count(csv.begin(), csv.end(), '\n')), frames + 1);
}

TEST(Take, WithTheSimulatedHandReRendersToTheByte) {
    expect_reproduced({"--haptic", "sim"}, test::temp_dir("take-hand"));
}

TEST(Take, FromAGestureFileReRendersToTheByte) {
    expect_reproduced({"--gesture", test::resource("gestures/detache.json").string()},
                      test::temp_dir("take-file"));
}

// The shipped 220 Hz string with position probes added on its masses, s1, s2, … in turn, until
// it has `probes`, written into dir; returns its path and fills `header` with probes.csv's
// first line.
std::filesystem::path string_with_probes(const std::filesystem::path& dir, std::size_t probes,
                                         std::string& header) {
    nlohmann::json model = read_json(test::resource("models/bowed-string-220.json"));
    header = "time";
    for (const auto& p : model["probes"]) header += "," + p["id"].get<std::string>();
    for (std::size_t i = model["probes"].size(); i < probes; ++i) {
        const std::string element = "s" + std::to_string(1 + i % 60);
        const std::string id = "x" + std::to_string(i);
        model["probes"].push_back({{"id", id}, {"kind", "position"}, {"element", element}});
        header += "," + id;
    }
    const auto path = dir / "probed.json";
    std::ofstream(path) << model.dump(1);
    return path;
}

// More probes than the engine streams to the studio (ipc::kMaxProbes): `play` records them all,
// where it once wrote the first sixteen into probes.csv and said nothing.
TEST(Take, RecordsEveryProbeOfAModelWithMoreThanTheStudioStreams) {
    const auto dir = test::temp_dir("take-many-probes");
    std::string header;
    const auto model = string_with_probes(dir, ipc::kMaxProbes + 5, header);
    expect_reproduced({"--haptic", "sim"}, dir, model);
    const std::string csv = test::read_file(dir / "take" / "probes.csv");
    EXPECT_EQ(csv.substr(0, csv.find('\n')), header) << "every probe has its column";
}

// A take whose writer falls behind (here with as many probes as a model may have: probes.csv
// then holds 1,024 numbers a sample, more than a writer formats in real time) never passes for
// whole. Whatever it lost, take.json counts, the player fails (status 1) and says so, and
// `render --take` warns; what it kept is whole rows. (A machine that kept up would have lost
// nothing, and then the take must be whole and succeed.)
TEST(Take, ATakeThatLostSamplesFailsAndSaysSo) {
    const auto dir = test::temp_dir("take-lost");
    std::string header;
    const auto model = string_with_probes(dir, limits::kProbes, header);
    const auto take = dir / "take";
    const auto r =
        test::run_archet({"play", model.string(), "--duration", "0.5", "--take", take.string()});
    const nlohmann::json description = read_json(take / "take.json");
    ASSERT_TRUE(description.is_object()) << r.err;
    const auto frames = description.value("frames", std::uint64_t{0});
    const auto lost_samples = description.value("dropped_samples", std::uint64_t{0});
    const auto lost_events = description.value("dropped_events", std::uint64_t{0});
    ASSERT_GT(frames, 0u) << r.err;
    EXPECT_EQ(frames_of(take / "take.wav"), static_cast<sf_count_t>(frames));
    // Read a line at a time: the rows run to tens of megabytes.
    std::ifstream csv(take / "probes.csv");
    std::string line, first;
    std::getline(csv, first);
    EXPECT_EQ(first, header);
    std::uint64_t rows = 0;
    bool whole = true;
    for (; std::getline(csv, line); ++rows)
        whole = whole && static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) ==
                             limits::kProbes;
    EXPECT_EQ(rows, frames) << "a row for each sample kept";
    EXPECT_TRUE(whole) << "every row holds the time and every probe";
    const auto again =
        test::run_archet({"render", "--take", take.string(), "-o", (dir / "again.wav").string()});
    ASSERT_EQ(again.status, 0) << again.err;
    if (lost_samples == 0 && lost_events == 0) {
        EXPECT_EQ(r.status, 0) << r.err;
        EXPECT_EQ(r.err.find("incomplete"), std::string::npos) << r.err;
        EXPECT_TRUE(same_bytes(dir / "again.wav", take / "take.wav"));
        return;
    }
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("the take is incomplete: it lost " + std::to_string(lost_samples) +
                         " samples and " + std::to_string(lost_events)),
              std::string::npos)
        << r.err;
    EXPECT_NE(again.err.find("lost " + std::to_string(lost_samples) + " samples and " +
                             std::to_string(lost_events)),
              std::string::npos)
        << again.err;
}

// take.json counts what a take lost only when it lost something (an Archet that knows no
// losses reads the rest), reads the counts back, and refuses a count that is not one.
TEST(TakeFile, CountsWhatATakeLostAndRefusesABadCount) {
    TakeDescription take;
    take.frames = 48000;
    EXPECT_EQ(format_take(take).find("dropped"), std::string::npos);
    take.dropped_samples = 120, take.dropped_events = 3;
    const TakeDescription back = parse_take(format_take(take), "take.json");
    EXPECT_EQ(back.dropped_samples, 120u);
    EXPECT_EQ(back.dropped_events, 3u);
    nlohmann::json bad = nlohmann::json::parse(format_take(take));
    bad["dropped_events"] = 2.5;
    try {
        parse_take(bad.dump(), "take.json");
        ADD_FAILURE() << "a fraction of an event was read";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("take.json.dropped_events"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("whole number of events"), std::string::npos)
            << e.what();
    }
    bad["dropped_events"] = 3, bad["dropped_samples"] = -1;
    EXPECT_THROW(parse_take(bad.dump(), "take.json"), InputError);
}

// `archet play --take`, started in the background.
pid_t spawn_play(const std::filesystem::path& take, const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args{
        ARCHET_BINARY, "play", test::resource("models/bowed-string-220.json").string(),
        "--duration",  "600",  "--take",
        take.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    // What it says goes to play.log beside the take.
    const std::string log = (take.parent_path() / "play.log").string();
    posix_spawn_file_actions_t files;
    ::posix_spawn_file_actions_init(&files);
    ::posix_spawn_file_actions_addopen(&files, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::posix_spawn_file_actions_adddup2(&files, 1, 2);
    pid_t pid = -1;
    const int failed = ::posix_spawn(&pid, argv[0], &files, nullptr, argv.data(), environ);
    ::posix_spawn_file_actions_destroy(&files);
    return failed ? -1 : pid;
}

// Waits for the process to end (generously: CI runs under ThreadSanitizer on two cores) and
// returns its wait status, or -1 if it never ended (then it is killed).
int wait_status(pid_t pid) {
    int status = -1;
    const bool ended = test::wait_for([&] { return ::waitpid(pid, &status, WNOHANG) == pid; },
                                      std::chrono::seconds(60));
    if (!ended) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, &status, 0);
        return -1;
    }
    return status;
}

// Files a finished command must not leave behind: temporaries, and a take's streams.
std::vector<std::string> leftovers(const std::filesystem::path& dir) {
    std::vector<std::string> found;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
        const std::string name = e.path().filename().string();
        if (name.find(".tmp-") != std::string::npos || e.path().extension() == ".jsonl")
            found.push_back(name);
    }
    return found;
}

constexpr std::uintmax_t kOneSecondOfWav = 48000 * 3;  // 24-bit mono at 48 kHz

class TakeSignal : public ::testing::TestWithParam<int> {};

// SIGINT, SIGTERM and SIGHUP finish the take: every file is written, take.json says it was
// interrupted and by what, the player exits 128 + the signal, and the take re-renders exactly.
TEST_P(TakeSignal, FinishesTheTakeCleanly) {
    const int signal = GetParam();
    const auto dir = test::temp_dir("take-signal-" + std::to_string(signal));
    const auto take = dir / "take";
    const pid_t pid = spawn_play(take);
    ASSERT_GT(pid, 0);
    // Once it has recorded a while: the take is under way.
    const bool recording = test::wait_for(
        [&] { return size_of(take / "take.wav") > kOneSecondOfWav / 2; }, std::chrono::seconds(60));
    ::kill(pid, signal);
    const int status = wait_status(pid);
    ASSERT_TRUE(recording) << "take.wav never grew";
    ASSERT_TRUE(WIFEXITED(status))
        << "ended by signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0)
        << " without finishing the take";
    EXPECT_EQ(WEXITSTATUS(status), 128 + signal);
    const std::string said = test::read_file(dir / "play.log");
    EXPECT_NE(said.find("take written to " + take.string()), std::string::npos) << said;
    EXPECT_NE(said.find(std::string("interrupted by SIG") + ::sigabbrev_np(signal)),
              std::string::npos)
        << said;

    const nlohmann::json description = read_json(take / "take.json");
    ASSERT_TRUE(description.is_object()) << "take.json is missing or damaged";
    EXPECT_EQ(description.value("complete", false), true);
    EXPECT_EQ(description.value("interrupted", false), true);
    EXPECT_EQ(description.value("interrupted_by", ""), std::string("SIG") + ::sigabbrev_np(signal));
    EXPECT_TRUE(std::filesystem::exists(take / "gesture.json"));
    EXPECT_EQ(leftovers(dir), std::vector<std::string>{});
    const sf_count_t frames = frames_of(take / "take.wav");
    EXPECT_EQ(description.value("frames", 0), frames);
    EXPECT_EQ(static_cast<std::uintmax_t>(frames) * 3 + 44, size_of(take / "take.wav"))
        << "the header counts every sample written";
    const std::string csv = test::read_file(take / "probes.csv");
    EXPECT_EQ(static_cast<sf_count_t>(std::count(csv.begin(), csv.end(), '\n')), frames + 1);

    const auto r =
        test::run_archet({"render", "--take", take.string(), "-o", (dir / "again.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("interrupted"), std::string::npos) << "render says so: " << r.err;
    EXPECT_EQ(test::read_file(dir / "again.wav"), test::read_file(take / "take.wav"))
        << "the interrupted take re-renders to the byte";
}

INSTANTIATE_TEST_SUITE_P(Take, TakeSignal, ::testing::Values(SIGINT, SIGTERM, SIGHUP),
                         [](const auto& info) { return std::string(::sigabbrev_np(info.param)); });

// After SIGKILL nothing could finish the take: `render --take` recovers what was recorded,
// repairs take.wav's header, says the take was interrupted, and reproduces every sample.
TEST(Take, AKilledTakeIsRecoveredByRender) {
    const auto dir = test::temp_dir("take-kill");
    const auto take = dir / "take";
    const pid_t pid =
        spawn_play(take, {"--gesture", test::resource("gestures/detache.json").string()});
    ASSERT_GT(pid, 0);
    const bool recording =
        test::wait_for([&] { return size_of(take / "take.wav") > kOneSecondOfWav * 3 / 4; },
                       std::chrono::seconds(60));
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    ASSERT_TRUE(recording) << "take.wav never grew";
    const std::uintmax_t recorded = (size_of(take / "take.wav") - 44) / 3;

    const auto r =
        test::run_archet({"render", "--take", take.string(), "-o", (dir / "again.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("interrupted"), std::string::npos) << "render says so: " << r.err;
    const std::vector<int> original = samples_of(take / "take.wav");
    EXPECT_EQ(original.size(), recorded) << "take.wav's header now counts all its samples";
    const std::vector<int> again = samples_of(dir / "again.wav");
    ASSERT_EQ(again.size(), original.size()) << "renders exactly the samples recorded";
    EXPECT_TRUE(again == original) << "the recovered take reproduces what was recorded";
    EXPECT_GT(*std::max_element(original.begin(), original.end()), 1 << 12) << "it was bowed";
    const nlohmann::json description = read_json(take / "take.json");
    EXPECT_EQ(description.value("interrupted", false), true);
    EXPECT_EQ(description.value("scheme", 0), kSchemeRevision) << "recovery keeps the revision";
    // And again, now that it is repaired: the same sound.
    const auto twice =
        test::run_archet({"render", "--take", take.string(), "-o", (dir / "twice.wav").string()});
    ASSERT_EQ(twice.status, 0) << twice.err;
    EXPECT_EQ(test::read_file(dir / "twice.wav"), test::read_file(dir / "again.wav"));
}

// Marks the take in `dir / name` as played under `revision`.
void mark_as_of(const std::filesystem::path& dir, const std::string& name, int revision) {
    nlohmann::json description = read_json(dir / name / "take.json");
    description["scheme"] = revision;
    std::ofstream(dir / name / "take.json") << description.dump(2);
}

// Marks the take in `dir / name` as played under `revision`, and renders it to
// `name`-`revision`.wav.
test::CommandResult render_as_of(const std::filesystem::path& dir, const std::string& name,
                                 int revision) {
    mark_as_of(dir, name, revision);
    return test::run_archet({"render", "--take", (dir / name).string(), "-o",
                             (dir / (name + "-" + std::to_string(revision) + ".wav")).string()});
}

// Plays `dir / name`.json for 0.3 s into the take `dir / name`, and holds its re-render under
// this revision to its take.wav, without a note.
void play_and_rerender(const std::filesystem::path& dir, const std::string& name) {
    auto r = test::run_archet({"play", (dir / (name + ".json")).string(), "--duration", "0.3",
                               "--take", (dir / name).string()});
    ASSERT_EQ(r.status, 0) << r.err;
    r = render_as_of(dir, name, kSchemeRevision);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("scheme revision"), std::string::npos) << r.err;
    EXPECT_EQ(test::read_file(dir / (name + "-" + std::to_string(kSchemeRevision) + ".wav")),
              test::read_file(dir / name / "take.wav"));
}

// A take records the scheme revision it was played with. One played before the scheme's
// arithmetic last changed re-renders to the byte if its model computes the same under both
// (the golden take, of revision 1: its string's grounds are not in the chain loop; the shipped
// string under revisions 2 and 3: its modal points have at most eight terms, and its friction
// divides as it did before revision 4), and with a note that it may differ by rounding if not
// (the shipped string's grounds since revision 2, a modal string's long points since
// revision 3) or by a fix (a finger by the bow's hair since revision 5); a revision this Archet
// does not know is refused.
TEST(Take, ATakeOfAnOlderSchemeSaysWhenItMayDiffer) {
    const auto dir = test::temp_dir("older_scheme");
    std::filesystem::copy(test::test_data("golden/take"), dir / "golden");
    auto r = test::run_archet(
        {"render", "--take", (dir / "golden").string(), "-o", (dir / "golden.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("scheme revision"), std::string::npos) << r.err;

    r = test::run_archet({"play", test::resource("models/bowed-string-220.json").string(),
                          "--duration", "0.3", "--take", (dir / "shipped").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    ASSERT_EQ(read_json(dir / "shipped" / "take.json")["scheme"], kSchemeRevision);
    r = render_as_of(dir, "shipped", 1);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("was played with scheme revision 1; this Archet computes its model "
                         "with revision " +
                         std::to_string(kSchemeRevision)),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("may differ from take.wav by rounding"), std::string::npos) << r.err;

    // A take of the shipped string played under revision 3 (golden_render_test holds its
    // re-render to the byte), and the same marked as played under revision 2.
    std::filesystem::copy(test::test_data("golden/take-revision-3"), dir / "played-3");
    r = test::run_archet(
        {"render", "--take", (dir / "played-3").string(), "-o", (dir / "played-3.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("scheme revision"), std::string::npos) << r.err;
    r = render_as_of(dir, "played-3", 2);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("scheme revision"), std::string::npos) << r.err;
    EXPECT_EQ(test::read_file(dir / "played-3-2.wav"), test::read_file(dir / "played-3.wav"))
        << "the shipped string computes the same under revisions 2 and 3: no note, same bytes";
    // Its probes show the friction to nine digits: marked as played under revision 4 it
    // re-renders with the reciprocals, and they differ (the sound's 24 bits hide it).
    const auto probes_as_of = [&](int revision) {
        mark_as_of(dir, "played-3", revision);
        const auto csv = dir / ("played-3-" + std::to_string(revision) + ".csv");
        const auto rendered =
            test::run_archet({"render", "--take", (dir / "played-3").string(), "--probes",
                              csv.string(), "-o", (dir / "probes.wav").string()});
        EXPECT_EQ(rendered.status, 0) << rendered.err;
        return test::read_file(csv);
    };
    EXPECT_NE(probes_as_of(3), probes_as_of(4)) << "render --take computes as the take's revision";

    // Revision 5, a fix: a string fingered between its bridge and the first mass under the
    // bow's hair (halfway, on 63 masses) re-renders as revision 5 computes, saying so.
    r = test::run_archet({"new", "bowed-string", "--masses", "63", "--finger", "--finger-position",
                          "0.0078125", "-o", (dir / "fingered.json").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    nlohmann::json fingered = read_json(dir / "fingered.json");
    for (auto& mass : fingered["masses"])
        if (mass["id"] == "bow_contact") mass["modes"] = {"s1", "s2", "s3"};
    std::ofstream(dir / "fingered.json") << fingered.dump(2);
    play_and_rerender(dir, "fingered");
    r = render_as_of(dir, "fingered", 4);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("was played with scheme revision 4"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("(a fix the take's revision lacked)"), std::string::npos) << r.err;

    // A string `archet new bowed-string` builds, played as a take and re-rendered to the byte;
    // then what render --take says of it marked as played under an older revision.
    const auto new_take = [&](const std::string& name, std::vector<std::string> options) {
        options.insert(options.begin(), {"new", "bowed-string"});
        options.insert(options.end(), {"-o", (dir / (name + ".json")).string()});
        const auto made = test::run_archet(options);
        ASSERT_EQ(made.status, 0) << made.err;
        play_and_rerender(dir, name);
    };
    const auto note_as_of = [&](const std::string& name, int revision) {
        const auto rendered = render_as_of(dir, name, revision);
        EXPECT_EQ(rendered.status, 0) << rendered.err;
        return rendered.err;
    };
    new_take("modal", {"--structure", "modal", "--masses", "30"});
    std::string said = note_as_of("modal", 2);
    EXPECT_NE(said.find("was played with scheme revision 2"), std::string::npos) << said;

    // Revision 6: the paper's modal string steps 3 of its 60 points (the others draw its shape),
    // and no longer counting the others takes its grounds into the chain loop.
    static_assert(kSchemeRevision == 6, "say which model computes differently since the newest");
    new_take("paper-modal", {"--paper", "--structure", "modal"});
    said = note_as_of("paper-modal", 5);
    EXPECT_NE(said.find("was played with scheme revision 5"), std::string::npos) << said;
    EXPECT_NE(said.find("by rounding"), std::string::npos) << said;
    said = note_as_of("shipped", 5);
    EXPECT_EQ(said.find("was played with"), std::string::npos) << "nothing changed for it";

    r = render_as_of(dir, "shipped", kSchemeRevision + 1);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("take.json.scheme"), std::string::npos) << r.err;
    EXPECT_FALSE(
        std::filesystem::exists(dir / ("shipped-" + std::to_string(kSchemeRevision + 1) + ".wav")));
}

// A take being recorded is not "recovered" under its recorder's feet: render refuses it.
TEST(Take, RenderRefusesATakeStillBeingRecorded) {
    const auto dir = test::temp_dir("take-busy-render");
    const auto take = dir / "take";
    const pid_t pid = spawn_play(take);
    ASSERT_GT(pid, 0);
    const bool recording = test::wait_for(
        [&] { return size_of(take / "take.wav") > kOneSecondOfWav / 4; }, std::chrono::seconds(60));
    const auto r =
        test::run_archet({"render", "--take", take.string(), "-o", (dir / "again.wav").string()});
    ::kill(pid, SIGTERM);
    const int status = wait_status(pid);
    ASSERT_TRUE(recording) << "take.wav never grew";
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("is being recorded right now"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "again.wav"));
    ASSERT_TRUE(WIFEXITED(status));
    const nlohmann::json description = read_json(take / "take.json");
    EXPECT_EQ(description.value("interrupted_by", ""), "SIGTERM") << "the player finished it";
}

// A take that clips says so, in take.json and on the terminal: the live limiter kept what
// was heard clean, but take.wav holds the model's own output.
TEST(Take, ClippingIsRecordedAndWarned) {
    const auto dir = test::temp_dir("take-clip");
    {
        std::ofstream(dir / "hard.json")
            << R"({"format": "archet-gesture", "version": 1, "name": "hard",
                  "keyframes": [{"t": 0, "slide": 0, "press": 0.1},
                                {"t": 1.2, "slide": 0.12, "press": 0.1}]})";
    }
    const auto r = test::run_archet(
        {"play", test::resource("models/bowed-string-220.json").string(), "--duration", "1",
         "--gesture", (dir / "hard.json").string(), "--take", (dir / "take").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json description = read_json(dir / "take" / "take.json");
    ASSERT_TRUE(description.is_object());
    const double clipped = description.value("clipped_samples", 0.0);
    EXPECT_GT(clipped, 1000) << description.dump();
    EXPECT_GE(description.value("peak", 0.0), 1.0);
    std::int64_t at_full_scale = 0;
    for (int s : samples_of(dir / "take" / "take.wav"))
        at_full_scale += s == 0x7FFFFF00 || s == std::numeric_limits<int>::min();
    EXPECT_EQ(clipped, static_cast<double>(at_full_scale)) << "counts the samples at full scale";
    EXPECT_NE(r.err.find("clipped"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("output_gain"), std::string::npos) << "says what to change: " << r.err;
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

// A take never holds non-finite sound (libsndfile writes NaN as full-scale DC): the first
// non-finite sample ends what it holds, and take.json says the simulation stopped being finite.
TEST(Take, ANonFiniteSampleEndsTheTakeAndSaysSo) {
    const auto dir = test::temp_dir("take-non-finite");
    {
        TakeRecorder take(dir / "take", build_bowed_string(BowedStringOptions{}), 48000, {"x"});
        take.begin(0);
        const double probe = 0.5;
        for (int i = 0; i < 100; ++i) take.sample((i + 1) / 48000.0, 0.25, &probe, 1);
        take.sample(101 / 48000.0, std::numeric_limits<double>::quiet_NaN(), &probe, 1);
        for (int i = 101; i < 200; ++i) take.sample((i + 1) / 48000.0, 0.25, &probe, 1);
        take.finish();
    }
    const std::vector<int> samples = samples_of(dir / "take" / "take.wav");
    EXPECT_EQ(samples.size(), 100u) << "nothing from the first non-finite sample on";
    for (int s : samples) EXPECT_GT(s, 0) << "no full-scale DC";
    const TakeDescription description = read_take_file(dir / "take" / "take.json");
    EXPECT_TRUE(description.interrupted);
    EXPECT_NE(description.interrupted_by.find("stopped being finite at t = 0.0021"),
              std::string::npos)
        << description.interrupted_by;
}

}  // namespace
}  // namespace archet

namespace archet {
namespace {

// A glide under way when a take began is kept with where it started and how far it got, in
// parameters.json and in the stream a killed take is recovered from; one that claims to have
// finished, or more than finished, is refused by name.
TEST(TakeParameters, AGlideUnderWayReadsBackAndAnImpossibleOneIsRefused) {
    ParameterChange under_way{960, "finger.position", 0.5, 480, 0.75, 12};
    const ParameterChange plain{1000, "friction.mu_s", 0.7, 480, std::nullopt, 0};
    const auto read = parse_parameter_changes(format_parameter_changes({under_way, plain}), "p");
    ASSERT_EQ(read.size(), 2u);
    ASSERT_TRUE(read[0].from.has_value());
    EXPECT_EQ(*read[0].from, 0.75);
    EXPECT_EQ(read[0].done, 12);
    EXPECT_FALSE(read[1].from.has_value());
    const auto line = parse_parameter_stream(format_parameter_line(under_way), "jsonl");
    ASSERT_EQ(line.size(), 1u);
    EXPECT_EQ(*line[0].from, 0.75);
    EXPECT_EQ(line[0].done, 12);
    under_way.done = 480;  // a glide that has made all its steps is not under way
    EXPECT_THROW(parse_parameter_changes(format_parameter_changes({under_way}), "p"), InputError);
    EXPECT_THROW(parse_parameter_stream(format_parameter_line(under_way), "jsonl"), InputError);
}

}  // namespace
}  // namespace archet

namespace archet {
namespace {

// A take begun while a parameter glides (the engine's way, in this process): the glide under
// way is carried into parameters.json, and `render --take` plays it on from where it was, to
// the byte.
TEST(TakeParameters, ATakeBegunMidGlideReRendersToTheByte) {
    const auto dir = test::temp_dir("take-mid-glide");
    BowedStringOptions o;
    o.pitch = 220, o.paper = true, o.finger = true;
    const Model model = build_bowed_string(o);
    Simulation sim(compile(model, 48000));
    const Gesture bow = steady_bow_gesture(0.1, 0.0015, 2.0);
    sim.set_gesture_track(&bow);
    const ParameterSlot finger = sim.model().resolve_parameter({"finger", "position"});
    ParameterSmoother smoother;
    for (int i = 0; i < 4800; ++i) smoother.advance(sim), sim.step();
    smoother.glide(sim, finger, 0.75, 480);  // 10 ms, as the engine glides
    for (int i = 0; i < 100; ++i) smoother.advance(sim), sim.step();
    ASSERT_EQ(smoother.active(), 1u) << "the take begins mid-glide";
    std::vector<std::string> probes;
    for (const auto& p : sim.model().probes) probes.push_back(p.id);
    {
        TakeRecorder take(dir / "take", model, 48000, probes, sim.state_size());
        take.name_slot(finger, "finger.position");
        sim.save_state(take.state_buffer());
        take.begin(sim.tick());
        for (const auto& g : smoother.glides()) take.glide_under_way(g);
        double values[ipc::kMaxProbes];
        for (int i = 0; i < 9600; ++i) {
            if (sim.tick() % 16 == 0)
                take.gesture(sim.time() + 16 / 48000.0, bow.at(sim.time() + 16 / 48000.0));
            smoother.advance(sim);
            sim.step();
            for (std::size_t p = 0; p < sim.probe_count(); ++p) values[p] = sim.probe(p);
            take.sample(sim.time(), sim.output(), values, sim.probe_count());
        }
        take.finish();
    }
    const auto changes = read_parameter_changes(dir / "take" / "parameters.json");
    ASSERT_EQ(changes.size(), 1u);
    ASSERT_TRUE(changes[0].from.has_value());
    EXPECT_EQ(changes[0].done, 100);
    const auto r = test::run_archet(
        {"render", "--take", (dir / "take").string(), "-o", (dir / "again.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(test::read_file(dir / "again.wav"), test::read_file(dir / "take" / "take.wav"));
}

}  // namespace
}  // namespace archet
