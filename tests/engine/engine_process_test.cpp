// The real-time engine as a real second process on shared memory: handshake, load a model,
// play it from the pad's gesture, receive probe frames and string shapes, change parameters,
// refuse bad commands and bad segments, and liveness both ways; the engine's boundaries: takes
// only inside the studio's take directory, the studio's pid fixed at start, a frozen studio's
// heartbeat, stale segments reclaimed, models too heavy for real time refused.

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>
#include <thread>

#include "archet/builders/bowed_string.hpp"
#include "archet/files/model_file.hpp"
#include "archet/link/engine_link.hpp"
#include "archet/model/string_points.hpp"
#include "test_support.hpp"

extern char** environ;

namespace archet::ipc {
namespace {

using link::EngineLink;
using link::EngineLinkOptions;

using namespace std::chrono_literals;

EngineLinkOptions options() {
    EngineLinkOptions o;
    o.archet_binary = ARCHET_BINARY;
    return o;
}

using test::wait_for;

// How long to wait for what the machine's speed decides: under TSan on two shared cores an
// engine starts, loads and plays many times slower. Tests wait for conditions, never for times.
constexpr std::chrono::milliseconds kGenerous{60000};

// Reads status frames until one of `kind` answers `sequence` (errors are collected).
bool wait_status(EngineLink& link, StatusKind kind, std::uint32_t sequence,
                 std::vector<std::string>& errors, std::chrono::milliseconds limit = kGenerous) {
    auto status = link.status();
    return wait_for(
        [&] {
            link.heartbeat();
            StatusFrame f;
            while (status.try_pop(f)) {
                if (f.kind == static_cast<std::uint32_t>(StatusKind::Error))
                    errors.push_back(f.text);
                if (f.kind == static_cast<std::uint32_t>(kind) && f.sequence == sequence)
                    return true;
            }
            return false;
        },
        limit);
}

// Waits for the engine's answer to a model load: ModelLoaded or Error with its sequence (and
// nothing if neither came within the limit), so that a test fails as soon as the wrong one does.
std::optional<StatusKind> load_answer(EngineLink& link, std::uint32_t sequence,
                                      std::vector<std::string>& errors,
                                      std::chrono::milliseconds limit = kGenerous) {
    auto status = link.status();
    std::optional<StatusKind> answer;
    wait_for(
        [&] {
            link.heartbeat();
            StatusFrame f;
            while (!answer && status.try_pop(f)) {
                if (f.kind == static_cast<std::uint32_t>(StatusKind::Error))
                    errors.push_back(f.text);
                const bool answers = f.kind == static_cast<std::uint32_t>(StatusKind::Error) ||
                                     f.kind == static_cast<std::uint32_t>(StatusKind::ModelLoaded);
                if (answers && f.sequence == sequence) answer = static_cast<StatusKind>(f.kind);
            }
            return answer.has_value();
        },
        limit);
    return answer;
}

// Starts the engine and plays the model file, or says in `error` why it could not.
bool start_playing_file(EngineLink& link, const std::filesystem::path& model, std::string& error) {
    link.start();
    if (!wait_for([&] { return link.liveness() == EngineLink::Liveness::Running; }, kGenerous)) {
        error = "the engine never ran";
        return false;
    }
    std::vector<std::string> errors;
    if (!wait_status(link, StatusKind::ModelLoaded, link.load_model(model.string()), errors)) {
        error = errors.empty() ? "the model never loaded" : errors[0];
        return false;
    }
    link.play();
    return true;
}

// Starts the engine, loads a shipped model and plays it.
bool start_playing(EngineLink& link, const std::string& resource) {
    std::string error;
    return start_playing_file(link, test::resource(resource), error);
}

// A parameter sent right behind a model load (here while the model before it may still be
// cross-fading in, when the real-time thread defers the swap) reaches the model that then
// plays; and the engine runs at the rate it was asked for, as its header says. (The window in which
// a deferred swap once lost the value, or applied it with the new model's slots to the old one, is
// a few milliseconds wide: this guards the behaviour, it cannot force the timing.)
TEST(EngineProcess, AParameterSentDuringASwapReachesTheModelThatPlays) {
    EngineLinkOptions o = options();
    o.sample_rate = 44100;
    EngineLink link(o);
    // The full-bandwidth strings use the 48 kHz scheme's whole band; the paper's runs at 44.1.
    ASSERT_TRUE(start_playing(link, "models/bowed-string-220-paper.json"));
    EXPECT_EQ(link.sample_rate(), 44100.0) << "in the segment's header";
    auto probes = link.probes();
    double normal = 0;
    // Bows on (pressed, moving), and reads the bow's normal force.
    // The stroke's time is the sound's (samples played), not the wall clock's.
    auto bow_until = [&](const std::function<bool()>& done) {
        std::uint64_t played = 0;
        return wait_for(
            [&] {
                const double t = static_cast<double>(played) / 44100;
                link.gesture(-0.05 + 0.05 * t, 0.0015);
                link.heartbeat();
                ProbeFrame f;
                while (probes.try_pop(f)) normal = f.values[4], ++played;  // normal_force
                return done();
            },
            kGenerous);
    };
    ASSERT_TRUE(bow_until([&] { return normal > 0.01; })) << "the pad presses the bow in";
    const std::string path = test::resource("models/bowed-string-220-paper.json").string();
    for (int round = 0; round < 6; ++round) {
        const bool inverted = round % 2 == 0;  // inverted press axis: no bow force
        std::vector<std::string> errors;
        ASSERT_TRUE(wait_status(link, StatusKind::ModelLoaded, link.load_model(path), errors));
        link.load_model(path);  // while the first is still cross-fading in
        link.send_parameter({"hand_press", "position_scale"}, inverted ? -1.0 : 1.0);
        EXPECT_TRUE(bow_until([&] { return inverted ? normal == 0.0 : normal > 0.01; }))
            << "round " << round << ": the value is in the model that plays (normal force "
            << normal << " N)";
    }
}

// The studio's link takes the rate and the block size the device runs at from the segment's
// header, where the engine writes them once its output is open (the null sink runs at what it
// is asked), and they agree with what the engine says of its device.
TEST(EngineProcess, TheLinkReadsTheRateAndBlockSizeFromTheHeader) {
    EngineLinkOptions o = options();
    o.sample_rate = 96000;
    o.block_frames = 256;
    EngineLink link(o);
    EXPECT_EQ(link.sample_rate(), 0.0) << "no device is open before the engine starts";
    EXPECT_EQ(link.block_frames(), 0u);
    link.start();
    ASSERT_TRUE(wait_for(
        [&] {
            link.heartbeat();
            return link.sample_rate() > 0 && link.block_frames() > 0;
        },
        kGenerous))
        << "the engine writes both once its output is open";
    EXPECT_EQ(link.sample_rate(), 96000.0);
    EXPECT_EQ(link.block_frames(), 256u);
    auto status = link.status();
    std::string said;
    ASSERT_TRUE(wait_for(
        [&] {
            link.heartbeat();
            StatusFrame f;
            while (said.empty() && status.try_pop(f))
                if (f.kind == static_cast<std::uint32_t>(StatusKind::Heartbeat)) said = f.text;
            return !said.empty();
        },
        kGenerous));
    EXPECT_NE(said.find(", 256 frames"), std::string::npos) << said;
}

TEST(EngineProcess, LoadsPlaysStreamsAndTakesParameters) {
    EngineLink link(options());
    link.start();
    ASSERT_TRUE(
        wait_for([&] { return link.liveness() == EngineLink::Liveness::Running; }, kGenerous));
    EXPECT_EQ(link.header().engine_pid.load(), link.engine_pid());

    std::vector<std::string> errors;
    const auto loaded = link.load_model(test::resource("models/bowed-string-220.json").string());
    ASSERT_TRUE(wait_status(link, StatusKind::ModelLoaded, loaded, errors))
        << (errors.empty() ? "" : errors[0]);
    const auto start = std::chrono::steady_clock::now();
    link.play();

    // Bow it from the pad: press, then a steady stroke at 0.1 m/s, for 36 000 samples (0.75 s
    // of sound), counted as they come, however long the machine takes to play them.
    auto probes = link.probes();
    std::uint64_t frames = 0, last_tick = 0;
    double max_friction = 0, last_energy = 0;
    bool ordered = true, finite = true, energy_held = true;
    int energy_changes = 0;
    ASSERT_TRUE(wait_for(
        [&] {
            const double t = static_cast<double>(frames) / 48000;  // the sound's own time
            link.gesture(0.1 * std::max(0.0, t - 0.05), std::min(0.0015, t * 0.05));
            link.heartbeat();
            ProbeFrame f;
            while (probes.try_pop(f)) {
                if (frames > 0 && f.tick != last_tick + 1) ordered = false;
                last_tick = f.tick, ++frames;
                for (std::uint32_t p = 0; p < f.count; ++p)
                    finite = finite && std::isfinite(f.values[p]);
                max_friction = std::max(max_friction, std::abs(f.values[5]));  // friction_force
                EXPECT_EQ(f.count, 11u);
                // The energy probe is read at every kEnergyProbeEvery-th tick and held in between.
                const double energy = f.values[9];
                if (f.tick % ipc::kEnergyProbeEvery != 0 && frames > 1 && energy != last_energy)
                    energy_held = false;
                energy_changes += energy != last_energy;
                last_energy = energy;
            }
            return frames >= 36000 && max_friction > 0.01;
        },
        kGenerous))
        << frames << " frames, friction " << max_friction;
    // Clocked in real time: never faster than 48 000 frames a second (a block's slack).
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LE(static_cast<double>(frames), 48000 * seconds + 2 * 64);
    EXPECT_TRUE(ordered) << "no frame lost while the reader keeps up";
    EXPECT_TRUE(finite);
    EXPECT_GT(max_friction, 0.01) << "the pad's gesture bowed the string";
    EXPECT_TRUE(energy_held) << "the scopes' energy changes only at every 16th tick";
    EXPECT_GT(energy_changes, 1000) << "and follows the string as it is bowed";

    auto shapes = link.shapes();
    ShapeFrame shape;
    ASSERT_TRUE(wait_for([&] { return shapes.try_pop(shape); }, kGenerous));
    const Model played = load_model_file(test::resource("models/bowed-string-220.json"));
    EXPECT_EQ(shape.count, string_points(played).size())
        << "the string: its bridge, its masses and its nut, not the bow or the body";

    // A parameter change takes effect: no bow force once the pressure axis is inverted.
    link.send_parameter({"hand_press", "position_scale"}, -1.0);
    double late_normal = 1;
    wait_for(
        [&] {
            ProbeFrame f;
            while (probes.try_pop(f)) late_normal = f.values[4];
            link.heartbeat();
            return late_normal == 0.0;
        },
        kGenerous);
    EXPECT_EQ(late_normal, 0.0);

    // Bad commands are answered with errors and change nothing.
    errors.clear();
    link.send_parameter({"nothing", "mass"}, 1);
    link.send_parameter({"k3", "stiffness"}, 1e12);
    link.load_model("/no/such/model.json");
    CommandFrame garbage{};
    std::memset(&garbage, 'x', sizeof garbage);
    link.send(garbage);
    const auto last = link.gesture(std::nan(""), 0);
    wait_status(link, StatusKind::Error, last, errors);
    ASSERT_EQ(errors.size(), 5u);
    EXPECT_NE(errors[0].find("no mass or link has this id"), std::string::npos) << errors[0];
    EXPECT_NE(errors[1].find("unstable"), std::string::npos) << errors[1];
    EXPECT_NE(errors[2].find("cannot open"), std::string::npos) << errors[2];
    EXPECT_NE(errors[3].find("not NUL-terminated"), std::string::npos) << errors[3];
    EXPECT_NE(errors[4].find("finite"), std::string::npos) << errors[4];
    EXPECT_EQ(link.liveness(), EngineLink::Liveness::Running);

    // Through all of it (a model swapped in, parameters, gestures, play) the real-time thread
    // never allocated.
    auto status = link.status();
    StatusFrame latest{};
    ASSERT_TRUE(wait_for(
        [&] {
            StatusFrame f;
            bool fresh = false;
            while (status.try_pop(f))
                if (f.kind == static_cast<std::uint32_t>(StatusKind::Heartbeat))
                    latest = f, fresh = true;
            return fresh && latest.blocks > 500;
        },
        kGenerous));
    EXPECT_GT(latest.blocks, 500u);
    EXPECT_EQ(latest.realtime_allocations, 0u);

    link.quit();
    ASSERT_TRUE(
        wait_for([&] { return link.liveness() == EngineLink::Liveness::Exited; }, kGenerous));
    EXPECT_EQ(link.exit_status(), 0);
}

// A string in modal form is drawn whole, as a chain is: the engine sends the positions of its
// bridge, of every mass's point and of its nut, though the step moves only the three points
// that its end links and its bow read (the others are summed from the modes for the frame).
TEST(EngineProcess, DrawsTheShapeOfAStringInModalForm) {
    BowedStringOptions o;
    o.pitch = 220, o.structure = Structure::Modal, o.paper = true;  // 60 masses
    const Model modal = build_bowed_string(o);
    const std::vector<std::string> points = string_points(modal);
    ASSERT_EQ(points.size(), 62u) << "the bridge, s1…s60 and the nut";
    std::size_t friction = modal.probes.size();
    for (std::size_t p = 0; p < modal.probes.size(); ++p)
        if (modal.probes[p].kind == ProbeKind::FrictionForce) friction = p;
    ASSERT_LT(friction, modal.probes.size());
    const auto dir = test::temp_dir("engine-modal-shape");
    write_file_atomically(dir / "modal.json", format_model(modal));

    EngineLink link(options());
    std::string error;
    ASSERT_TRUE(start_playing_file(link, dir / "modal.json", error)) << error;
    auto probes = link.probes();
    std::uint64_t frames = 0;
    double max_friction = 0;
    ASSERT_TRUE(wait_for(
        [&] {
            const double t = static_cast<double>(frames) / 48000;
            link.gesture(0.1 * std::max(0.0, t - 0.05), std::min(0.0015, t * 0.05));
            link.heartbeat();
            ProbeFrame f;
            while (probes.try_pop(f)) {
                ++frames;
                max_friction = std::max(max_friction, std::abs(f.values[friction]));
            }
            return frames >= 24000 && max_friction > 0.01;
        },
        kGenerous))
        << frames << " frames, friction " << max_friction;

    // A frame of the bowed string, every point away from its rest (that each is where the
    // chaplet's mass would be, modal_structure_test.cpp holds).
    auto shapes = link.shapes();
    ShapeFrame shape{};
    double peak = 0;
    ASSERT_TRUE(wait_for(
        [&] {
            link.heartbeat();
            while (shapes.try_pop(shape)) {
                peak = 0;
                for (std::uint32_t i = 0; i < shape.count; ++i)
                    peak = std::max(peak, std::abs(double{shape.positions[i]}));
                if (shape.count == points.size() && peak > 0) return true;
            }
            return false;
        },
        kGenerous))
        << "the last frame has " << shape.count << " points, of peak " << peak;
    int moved = 0;
    for (std::uint32_t i = 1; i + 1 < shape.count; ++i) moved += shape.positions[i] != 0.0f;
    EXPECT_EQ(moved, 60) << "each mass's point, not only the three the step moves";
}

// A string longer than a shape frame holds (ipc::kMaxShapePoints) is drawn from points spread
// evenly along it, from its first end to its last, where it was once cut off after its 512th.
// A chain of 600 masses, plucked and left to ring (no bow: every MAT is the string), its ends
// fixed.
TEST(EngineProcess, DrawsAStringLongerThanAFrameFromEndToEnd) {
    constexpr int kMasses = 600;
    const Model plucked = test::plucked_chain(kMasses);
    const std::vector<std::string> points = string_points(plucked);
    ASSERT_EQ(points.size(), kMasses + 2u) << "the two ends and every mass";
    ASSERT_GT(points.size(), kMaxShapePoints);
    const auto dir = test::temp_dir("engine-long-shape");
    write_file_atomically(dir / "plucked.json", format_model(plucked));

    EngineLink link(options());
    std::string error;
    ASSERT_TRUE(start_playing_file(link, dir / "plucked.json", error)) << error;
    auto shapes = link.shapes();
    ShapeFrame shape{};
    ASSERT_TRUE(wait_for(
        [&] {
            link.heartbeat();
            return shapes.try_pop(shape);
        },
        kGenerous));
    EXPECT_EQ(shape.count, kMaxShapePoints);
    EXPECT_EQ(shape.spread_over, points.size());
    // Drawn from the first end to the last: both fixed at 0, every mass drawn between them
    // away from rest (cut off, the last point drawn was m511, mid-string).
    const std::vector<std::size_t> drawn = drawn_points(points.size(), kMaxShapePoints);
    ASSERT_EQ(drawn.size(), kMaxShapePoints);
    EXPECT_EQ(drawn.front(), 0u);
    EXPECT_EQ(drawn.back(), points.size() - 1);
    EXPECT_EQ(shape.positions[0], 0.0f);
    EXPECT_EQ(shape.positions[kMaxShapePoints - 1], 0.0f) << "the far end, fixed";
    std::size_t moved = 0;
    for (std::size_t i = 1; i + 1 < kMaxShapePoints; ++i) moved += shape.positions[i] != 0.0f;
    EXPECT_EQ(moved, kMaxShapePoints - 2) << "the masses between the ends";
}

TEST(EngineProcess, ARunawayIsMutedWithinABlockAndTheModelReset) {
    EngineLink link(options());
    ASSERT_TRUE(start_playing(link, "models/bowed-string-220.json"));
    std::vector<std::string> errors;
    link.gesture(0.0, 60.0);  // the pad shoves the bow 60 m into the string: kilojoules
    auto status = link.status();
    bool blown = false;
    ASSERT_TRUE(wait_for(
        [&] {
            StatusFrame f;
            while (status.try_pop(f))
                blown = blown || f.kind == static_cast<std::uint32_t>(StatusKind::Blowup);
            link.heartbeat();
            return blown;
        },
        kGenerous));
    // Whatever came out before the mute stayed finite (the limiter holds full scale downstream).
    auto probes = link.probes();
    ProbeFrame f;
    while (probes.try_pop(f)) ASSERT_TRUE(std::isfinite(f.output));
    link.gesture(0.0, 0.0);  // let go: the reset model plays on
    EXPECT_EQ(link.liveness(), EngineLink::Liveness::Running);
}

TEST(EngineProcess, SwapsModelsWithoutAClick) {
    EngineLink link(options());
    ASSERT_TRUE(start_playing(link, "models/bowed-string-220.json"));
    std::vector<std::string> errors;
    auto probes = link.probes();
    std::vector<double> played;
    std::uint64_t swap_tick = 0;
    // Bows (0.1 m/s across, pressed) until `frames` samples have been played in all: counted in
    // the sound, not in wall-clock time, which a slow machine (TSan) stretches. The stroke is
    // timed in the sound too: the second call goes on where the first left the bow (timed on
    // the wall clock, a slow first call left it further on, and the bow jumped back: a click).
    auto bow_until = [&](std::size_t frames, double from) {
        const std::size_t start = played.size();
        return wait_for(
            [&] {
                const double t = static_cast<double>(played.size() - start) / 48000;
                link.gesture(from + 0.1 * t, 0.0015);
                link.heartbeat();
                ProbeFrame f;
                while (probes.try_pop(f)) played.push_back(f.output);
                return played.size() >= frames;
            },
            kGenerous);
    };
    ASSERT_TRUE(bow_until(33600, 0.0)) << "0.7 s of sound";
    swap_tick = played.size();
    const auto sequence =
        link.load_model(test::resource("models/bowed-string-220-harmonic.json").string());
    ASSERT_TRUE(bow_until(swap_tick + 14400, 0.07)) << "0.3 s more";
    ASSERT_TRUE(wait_status(link, StatusKind::ModelLoaded, sequence, errors));
    // The largest step between samples while the old string sang steadily, against the
    // largest step anywhere after the swap was asked for.
    double steady = 0, around_swap = 0;
    for (std::size_t i = swap_tick / 2; i < swap_tick; ++i)
        steady = std::max(steady, std::abs(played[i] - played[i - 1]));
    for (std::size_t i = swap_tick; i < played.size(); ++i)
        around_swap = std::max(around_swap, std::abs(played[i] - played[i - 1]));
    ASSERT_GT(steady, 0.0) << "it was playing";
    EXPECT_LT(around_swap, 1.5 * steady) << "a click at the swap";
}

TEST(EngineProcess, ThePadMovesASimulatedHandThatFeelsTheString) {
    EngineLinkOptions o = options();
    o.haptic = "sim";
    EngineLink link(o);
    ASSERT_TRUE(start_playing(link, "models/bowed-string-220.json"));
    std::vector<std::string> errors;
    auto probes = link.probes();
    double max_friction = 0, max_hand_force = 0;
    std::uint64_t frames = 0;
    // Bows until the hand has bowed the string and felt it, in the sound's own time.
    wait_for(
        [&] {
            const double t = static_cast<double>(frames) / 48000;
            link.gesture(0.1 * t, 0.0015);  // the mouse: the hand follows it through its grip
            link.heartbeat();
            ProbeFrame f;
            while (probes.try_pop(f)) {
                ++frames;
                max_friction = std::max(max_friction, std::abs(f.values[5]));
                max_hand_force =
                    std::max(max_hand_force, std::abs(f.values[7]));  // hand_force_slide
            }
            return max_friction > 0.01 && max_hand_force > 0.01;
        },
        kGenerous);
    EXPECT_GT(max_friction, 0.01) << "the hand bowed the string";
    EXPECT_GT(max_hand_force, 0.01) << "and felt it";
    auto status = link.status();
    StatusFrame latest{};
    ASSERT_TRUE(wait_for(
        [&] {
            StatusFrame f;
            bool fresh = false;
            while (status.try_pop(f)) latest = f, fresh = true;
            link.heartbeat();
            return fresh;
        },
        kGenerous));
    EXPECT_EQ(latest.realtime_allocations, 0u);
}

TEST(EngineProcess, StudioTellsUnresponsiveFromExited) {
    EngineLink link(options());
    link.start();
    ASSERT_TRUE(
        wait_for([&] { return link.liveness() == EngineLink::Liveness::Running; }, kGenerous));
    ::kill(link.engine_pid(), SIGSTOP);
    EXPECT_TRUE(
        wait_for([&] { return link.liveness() == EngineLink::Liveness::Unresponsive; }, kGenerous));
    ::kill(link.engine_pid(), SIGCONT);
    EXPECT_TRUE(
        wait_for([&] { return link.liveness() == EngineLink::Liveness::Running; }, kGenerous));
    ::kill(link.engine_pid(), SIGKILL);
    EXPECT_TRUE(
        wait_for([&] { return link.liveness() == EngineLink::Liveness::Exited; }, kGenerous));
}

TEST(EngineProcess, EngineExitsWithinASecondWhenTheStudioDies) {
    int pipe_fds[2];
    ASSERT_EQ(::pipe(pipe_fds), 0);
    const pid_t studio = ::fork();
    ASSERT_GE(studio, 0);
    if (studio == 0) {  // a studio that starts an engine and then crashes
        EngineLink link(options());
        link.start();
        const pid_t engine = link.engine_pid();
        char name[64] = {};
        std::strncpy(name, link.segment_name().c_str(), sizeof name - 1);
        if (::write(pipe_fds[1], &engine, sizeof engine) < 0 ||
            ::write(pipe_fds[1], name, sizeof name) < 0)
            ::_exit(1);
        // Until the engine runs, however long it takes to start (then it is the studio that dies).
        for (int i = 0; i < 60000 && link.liveness() != EngineLink::Liveness::Running; ++i)
            ::usleep(1000);
        ::_exit(0);  // no destructor: no quit, no unlink
    }
    pid_t engine = -1;
    char name[64] = {};
    ASSERT_EQ(::read(pipe_fds[0], &engine, sizeof engine), static_cast<ssize_t>(sizeof engine));
    ASSERT_EQ(::read(pipe_fds[0], name, sizeof name), static_cast<ssize_t>(sizeof name));
    ::waitpid(studio, nullptr, 0);
    const auto died = std::chrono::steady_clock::now();
    // Exited: gone, or a zombie waiting for whoever adopted it to reap it.
    auto exited = [&] {
        if (::kill(engine, 0) != 0 && errno == ESRCH) return true;
        const std::string stat = test::read_file("/proc/" + std::to_string(engine) + "/stat");
        const auto close = stat.rfind(')');
        return close != std::string::npos && close + 2 < stat.size() && stat[close + 2] == 'Z';
    };
    const bool gone = wait_for(exited, kGenerous);
    const auto took = std::chrono::steady_clock::now() - died;
    ASSERT_TRUE(gone) << "the orphaned engine kept running";
    EXPECT_LT(took, 1000ms);
    const int fd = ::shm_open(name, O_RDONLY, 0);
    EXPECT_LT(fd, 0) << "the engine removed the dead studio's segment";
    if (fd >= 0) ::close(fd), ::shm_unlink(name);
}

TEST(EngineProcess, RefusesAMissingOrCorruptSegment) {
    auto r = test::run_archet({"engine", "--shm", "/archet-does-not-exist"});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("cannot open"), std::string::npos) << r.err;
    SharedSegment segment = SharedSegment::create(plan_layout(8, 8, 2, 8));
    segment.header().probes.frame_size = 7;  // a hostile or mismatched studio
    r = test::run_archet({"engine", "--shm", segment.name()});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("frame size"), std::string::npos) << r.err;
    segment.header().probes.frame_size = sizeof(ProbeFrame);
    segment.header().magic = 0;
    r = test::run_archet({"engine", "--shm", segment.name()});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("bad magic"), std::string::npos) << r.err;
}

// What lies directly in `dir`: names, for seeing that nothing was created.
std::set<std::string> entries(const std::filesystem::path& dir) {
    std::set<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        names.insert(e.path().filename().string());
    return names;
}

// A StartTake folder comes from another process: it must be absolute, printable, plain (no
// "." or ".."), and inside the take directory the studio gave at start, symbolic links
// resolved. Anything else is refused before a folder is made, with the path quoted safely.
TEST(EngineProcess, RecordsTakesOnlyInsideTheStudiosTakeDirectory) {
    const auto root = test::temp_dir("engine-takes-root");
    const auto outside = test::temp_dir("engine-takes-outside");
    std::filesystem::create_directory_symlink(outside, root / "link");
    EngineLinkOptions o = options();
    o.takes = (root / "takes").string();  // made by the engine
    EngineLink link(o);
    ASSERT_TRUE(start_playing(link, "models/bowed-string-220.json"));
    const auto cwd = std::filesystem::current_path();  // the engine's too
    for (const auto& left : {cwd / "relative-take", cwd.parent_path() / "x"})
        std::filesystem::remove_all(left);  // what an engine that did not check once made
    const std::string refused[] = {
        "relative-take",
        "/tmp/\x01\xfe\x7f\x1b[2Jtake",
        "../x",
        (root / "takes" / ".." / "escaped").string(),
        (outside / "take").string(),
        (root / "link" / "take").string(),  // inside by name, outside once the link is resolved
        root.string(),                      // the parent of the take directory
    };
    std::vector<std::string> errors;
    for (const std::string& folder : refused) {
        errors.clear();
        const auto sequence = link.start_take(folder);
        ASSERT_TRUE(wait_status(link, StatusKind::Error, sequence, errors)) << folder;
        ASSERT_FALSE(errors.empty());
        const std::string& said = errors.back();
        EXPECT_NE(said.find("take folder \""), std::string::npos) << said;
        for (char c : said)
            EXPECT_TRUE(static_cast<unsigned char>(c) >= 0x20 && c != 0x7f)
                << "a control byte quoted raw: " << said;
    }
    EXPECT_NE(errors.size(), 0u);
    link.stop_take();
    // Nothing was made: not in the engine's working folder, its parent, the temporary folder,
    // the take directory or the folder outside it.
    EXPECT_FALSE(std::filesystem::exists(cwd / "relative-take"));
    EXPECT_FALSE(std::filesystem::exists(cwd.parent_path() / "x"));
    EXPECT_FALSE(std::filesystem::exists(refused[1]));
    EXPECT_EQ(entries(root), (std::set<std::string>{"link", "takes"}));
    EXPECT_TRUE(entries(root / "takes").empty());
    EXPECT_TRUE(entries(outside).empty());
    // What each refusal says to change.
    auto refusal = [&](const std::string& folder) {
        errors.clear();
        wait_status(link, StatusKind::Error, link.start_take(folder), errors);
        return errors.empty() ? std::string() : errors.back();
    };
    EXPECT_NE(refusal("relative-take").find("is relative: give an absolute path inside"),
              std::string::npos);
    const std::string binary = refusal(refused[1]);
    EXPECT_NE(binary.find("\\x01\\xfe\\x7f\\x1b[2Jtake"), std::string::npos) << binary;
    EXPECT_NE(binary.find("non-printable"), std::string::npos) << binary;
    EXPECT_NE(refusal(refused[3]).find("\"..\""), std::string::npos);
    EXPECT_NE(refusal(refused[4]).find("is not inside the take directory"), std::string::npos);

    // A folder inside it records.
    errors.clear();
    const auto good = (root / "takes" / "2026-12-01-take").string();
    ASSERT_TRUE(wait_status(link, StatusKind::Take, link.start_take(good), errors))
        << (errors.empty() ? "" : errors.back());
    link.stop_take();
    auto status = link.status();
    ASSERT_TRUE(wait_for(
        [&] {
            link.heartbeat();
            StatusFrame f;
            while (status.try_pop(f))
                if (f.kind == static_cast<std::uint32_t>(StatusKind::Take) &&
                    std::string(f.text).rfind("written ", 0) == 0)
                    return true;
            return false;
        },
        kGenerous));
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(good) / "take.wav"));
}

// Forks a studio that starts an engine, lets `before_dying` act on its link, and exits
// without cleaning up (a crash). Returns the engine's pid and the segment's name.
std::pair<pid_t, std::string> crashing_studio(
    const std::function<void(EngineLink&)>& before_dying) {
    int pipe_fds[2];
    if (::pipe(pipe_fds) != 0) return {-1, ""};
    const pid_t studio = ::fork();
    if (studio == 0) {
        EngineLink link(options());
        link.start();
        for (int i = 0; i < 20000 && link.liveness() != EngineLink::Liveness::Running; ++i)
            ::usleep(1000);
        before_dying(link);
        const pid_t engine = link.engine_pid();
        char name[64] = {};
        std::strncpy(name, link.segment_name().c_str(), sizeof name - 1);
        if (::write(pipe_fds[1], &engine, sizeof engine) < 0 ||
            ::write(pipe_fds[1], name, sizeof name) < 0)
            ::_exit(1);
        ::_exit(0);  // no destructor: no quit, no unlink
    }
    pid_t engine = -1;
    char name[64] = {};
    if (::read(pipe_fds[0], &engine, sizeof engine) != static_cast<ssize_t>(sizeof engine) ||
        ::read(pipe_fds[0], name, sizeof name) != static_cast<ssize_t>(sizeof name))
        engine = -1;
    ::close(pipe_fds[0]), ::close(pipe_fds[1]);
    ::waitpid(studio, nullptr, 0);
    return {engine, name};
}

// Gone, or a zombie waiting for whoever adopted it to reap it.
bool exited(pid_t pid) {
    if (::kill(pid, 0) != 0 && errno == ESRCH) return true;
    const std::string stat = test::read_file("/proc/" + std::to_string(pid) + "/stat");
    const auto close = stat.rfind(')');
    return close != std::string::npos && close + 2 < stat.size() && stat[close + 2] == 'Z';
}

// The engine watches the studio it was started by, not whatever pid the header holds later:
// a studio (or anything else) writing 1 (init, which never dies) there left an orphan engine.
TEST(EngineProcess, WatchesTheStudioItStartedWithWhateverTheHeaderSaysLater) {
    const auto crashed = crashing_studio([](EngineLink& link) { link.header().studio_pid = 1; });
    const pid_t engine = crashed.first;
    const std::string name = crashed.second;
    ASSERT_GT(engine, 0);
    const bool gone = wait_for([&] { return exited(engine); }, kGenerous);
    if (!gone) ::kill(engine, SIGKILL);  // it holds ctest's output pipe open
    ASSERT_TRUE(gone) << "an orphaned engine";
    const int fd = ::shm_open(name.c_str(), O_RDONLY, 0);
    EXPECT_LT(fd, 0) << "the engine removed the dead studio's segment";
    if (fd >= 0) ::close(fd), ::shm_unlink(name.c_str());
}

// An engine started by some other process than the segment's owner (no death signal from the
// kernel) watches the owner by a pidfd taken at start, not by the pid the header holds later.
TEST(EngineProcess, AnEngineNotStartedByItsStudioWatchesTheOwnerItAttachedTo) {
    int name_pipe[2], go_pipe[2];
    ASSERT_EQ(::pipe(name_pipe), 0);
    ASSERT_EQ(::pipe(go_pipe), 0);
    const pid_t studio = ::fork();
    ASSERT_GE(studio, 0);
    if (studio == 0) {  // owns a segment, then writes 1 over its pid and crashes
        SharedSegment segment = SharedSegment::create(plan_layout(256, 1u << 12, 64, 256));
        char name[64] = {};
        std::strncpy(name, segment.name().c_str(), sizeof name - 1);
        char go = 0;
        if (::write(name_pipe[1], name, sizeof name) < 0 || ::read(go_pipe[0], &go, 1) != 1)
            ::_exit(1);
        segment.header().studio_pid = 1;
        ::_exit(0);  // no destructor: no unlink
    }
    char name[64] = {};
    ASSERT_EQ(::read(name_pipe[0], name, sizeof name), static_cast<ssize_t>(sizeof name));
    std::string binary = ARCHET_BINARY, engine_word = "engine", shm = "--shm", segment_name = name;
    std::vector<char*> argv{binary.data(), engine_word.data(), shm.data(), segment_name.data(),
                            nullptr};
    pid_t engine = -1;
    ASSERT_EQ(::posix_spawn(&engine, binary.c_str(), nullptr, nullptr, argv.data(), environ), 0);
    {
        SharedSegment seen = SharedSegment::attach(name);
        EXPECT_TRUE(wait_for(
            [&] {
                return seen.header().engine_state.load() ==
                       static_cast<std::uint32_t>(EngineState::Ready);
            },
            kGenerous))
            << "the engine attached";
    }
    ASSERT_EQ(::write(go_pipe[1], "g", 1), 1);
    ::waitpid(studio, nullptr, 0);
    int status = -1;
    const bool gone =
        wait_for([&] { return ::waitpid(engine, &status, WNOHANG) == engine; }, kGenerous);
    if (!gone) ::kill(engine, SIGKILL), ::waitpid(engine, nullptr, 0);
    EXPECT_TRUE(gone) << "the engine outlived the studio it attached to";
    EXPECT_FALSE(::shm_open(name, O_RDONLY, 0) >= 0) << "and left its segment behind";
    ::shm_unlink(name);
    for (int fd : {name_pipe[0], name_pipe[1], go_pipe[0], go_pipe[1]}) ::close(fd);
}

// A process that bumps the studio's heartbeat in `link`'s segment (the mapping is shared
// across fork) until it is killed: the studio's role, to freeze with SIGSTOP.
pid_t heartbeat_process(EngineLink& link) {
    const pid_t beater = ::fork();
    if (beater == 0) {
        for (;;) {
            link.heartbeat();
            ::usleep(5000);
        }
    }
    return beater;
}

// A frozen studio (SIGSTOP) cannot hear or steer: after the heartbeat timeout the engine fades
// out and plays nothing, says so, and plays again when the heartbeat moves (SIGCONT).
TEST(EngineProcess, AFrozenStudioSilencesTheEngineUntilItBeatsAgain) {
    EngineLinkOptions o = options();
    o.studio_timeout = 1000ms;
    EngineLink link(o);
    ASSERT_TRUE(start_playing(link, "models/bowed-string-220.json"));
    const pid_t studio = heartbeat_process(link);  // from here on only it beats
    ASSERT_GT(studio, 0);
    auto probes = link.probes();
    auto status = link.status();
    std::uint64_t blocks = 0;
    std::string said;
    auto watch = [&] {
        StatusFrame f;
        while (status.try_pop(f)) {
            blocks = f.blocks;
            if (std::string(f.text).rfind("silent", 0) == 0) said = f.text;
        }
    };
    // Bows until the string sounds; `frames` counts the probe frames, `loud` the largest output.
    std::uint64_t frames = 0;
    double loud = 0;
    const auto start = std::chrono::steady_clock::now();
    auto bow = [&] {
        const double t =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        link.gesture(-0.05 + 0.05 * std::fmod(t, 2.0), 0.0015);
        ProbeFrame f;
        while (probes.try_pop(f)) ++frames, loud = std::max(loud, std::abs(f.output));
        watch();
    };
    ASSERT_TRUE(wait_for([&] { return bow(), loud > 1e-4; }, kGenerous)) << "it sounds";

    ::kill(studio, SIGSTOP);
    auto state = [&] { return static_cast<EngineState>(link.header().engine_state.load()); };
    // The state changes first, then the status frame that says why: wait for both.
    EXPECT_TRUE(wait_for([&] { return bow(), state() == EngineState::Silent && !said.empty(); },
                         kGenerous));
    EXPECT_NE(said.find("heartbeat stopped"), std::string::npos) << said;
    // Past the fade (10 ms, a few blocks), nothing plays while the device's clock runs on.
    const std::uint64_t silent_at = blocks;
    ASSERT_TRUE(wait_for([&] { return bow(), blocks > silent_at + 40; }, kGenerous));
    frames = 0, loud = 0;
    const std::uint64_t quiet_from = blocks;
    ASSERT_TRUE(wait_for([&] { return bow(), blocks > quiet_from + 100; }, kGenerous));
    EXPECT_EQ(frames, 0u) << "the model was not stepped";
    EXPECT_EQ(loud, 0.0);
    EXPECT_EQ(state(), EngineState::Silent);

    ::kill(studio, SIGCONT);
    EXPECT_TRUE(wait_for([&] { return bow(), state() == EngineState::Ready; }, kGenerous));
    EXPECT_TRUE(wait_for([&] { return bow(), loud > 1e-4; }, kGenerous)) << "the sound is back";
    ::kill(studio, SIGKILL);
    ::waitpid(studio, nullptr, 0);
    EXPECT_EQ(link.liveness(), EngineLink::Liveness::Running);
}

// Ctrl+Z stops the studio and its engine together (one process group). An engine stopped for
// longer than the give-up time does not take its own stop for the studio's silence when it
// wakes before the studio has had its turn to beat.
TEST(EngineProcess, AnEngineStoppedWithItsStudioPlaysOnWhenBothWake) {
    EngineLinkOptions o = options();
    o.studio_timeout = 300ms;
    o.studio_give_up = 1000ms;
    EngineLink link(o);
    link.start();
    ASSERT_TRUE(wait_for(
        [&] {
            link.heartbeat();
            return link.liveness() == EngineLink::Liveness::Running;
        },
        kGenerous));
    auto rounds = [&] { return link.header().engine_heartbeat.load(); };
    // The engine has seen the studio's last beat before both stop.
    const auto seen_from = rounds();
    ASSERT_TRUE(wait_for([&] { return rounds() > seen_from + 5; }, kGenerous));
    const pid_t engine = link.engine_pid();
    ::kill(engine, SIGSTOP);
    std::this_thread::sleep_for(1500ms);  // the length of the stop, longer than the give-up
    ::kill(engine, SIGCONT);
    // The engine runs its rounds first; the studio (this test) has not beaten yet.
    const auto woke_at = rounds();
    EXPECT_TRUE(wait_for(
        [&] { return rounds() > woke_at + 20 || link.liveness() == EngineLink::Liveness::Exited; },
        kGenerous));
    // Then the studio beats again, and the engine is still there to hear it.
    const auto beating_from = rounds();
    EXPECT_TRUE(wait_for(
        [&] {
            link.heartbeat();
            return rounds() > beating_from + 200;
        },
        kGenerous));
    EXPECT_EQ(link.liveness(), EngineLink::Liveness::Running);
}

// A studio frozen for good: the engine gives up after the longer timeout and exits.
TEST(EngineProcess, AStudioFrozenForGoodLetsTheEngineExit) {
    EngineLinkOptions o = options();
    o.studio_timeout = 500ms;
    o.studio_give_up = 2000ms;
    EngineLink link(o);
    link.start();
    ASSERT_TRUE(
        wait_for([&] { return link.liveness() == EngineLink::Liveness::Running; }, kGenerous));
    const pid_t studio = heartbeat_process(link);
    ASSERT_GT(studio, 0);
    ::kill(studio, SIGSTOP);
    EXPECT_TRUE(
        wait_for([&] { return link.liveness() == EngineLink::Liveness::Exited; }, kGenerous));
    EXPECT_EQ(link.exit_status(), 0);
    ::kill(studio, SIGKILL);
    ::waitpid(studio, nullptr, 0);
}

// A segment made by a process that then died without unlinking it.
std::string abandoned_segment(const std::function<void(SharedSegment&)>& change = {}) {
    int pipe_fds[2];
    if (::pipe(pipe_fds) != 0) return "";
    const pid_t owner = ::fork();
    if (owner == 0) {
        SharedSegment segment = SharedSegment::create(plan_layout(8, 8, 2, 8));
        if (change) change(segment);
        char name[64] = {};
        std::strncpy(name, segment.name().c_str(), sizeof name - 1);
        if (::write(pipe_fds[1], name, sizeof name) < 0) ::_exit(1);
        ::_exit(0);  // no destructor: no unlink
    }
    char name[64] = {};
    if (::read(pipe_fds[0], name, sizeof name) != static_cast<ssize_t>(sizeof name)) name[0] = 0;
    ::close(pipe_fds[0]), ::close(pipe_fds[1]);
    ::waitpid(owner, nullptr, 0);
    return name;
}

bool segment_exists(const std::string& name) {
    const int fd = ::shm_open(name.c_str(), O_RDONLY, 0);
    if (fd >= 0) ::close(fd);
    return fd >= 0;
}

// When a studio and its engine both died, neither removed their segment: the next studio to
// start an engine does, and leaves every segment that still has a living side, or that is not
// a valid Archet segment.
TEST(EngineProcess, TheNextStartReclaimsTheSegmentOfAStudioAndEngineThatBothDied) {
    const std::string stale = abandoned_segment();
    const std::string engine_lives = abandoned_segment();
    const std::string foreign = abandoned_segment([](SharedSegment& s) { s.header().magic = 0; });
    ASSERT_FALSE(stale.empty());
    ASSERT_FALSE(engine_lives.empty());
    ASSERT_FALSE(foreign.empty());
    const pid_t engine = ::fork();  // a living "engine" for the second one
    if (engine == 0) {
        for (;;) ::pause();
    }
    {
        SharedSegment s = SharedSegment::attach(engine_lives);
        s.header().engine_pid.store(engine);
    }
    SharedSegment ours = SharedSegment::create(plan_layout(8, 8, 2, 8));  // its studio lives
    ASSERT_TRUE(segment_exists(stale));

    EngineLink link(options());
    link.start();
    EXPECT_FALSE(segment_exists(stale)) << "both its processes are gone";
    EXPECT_TRUE(segment_exists(engine_lives)) << "its engine lives";
    EXPECT_TRUE(segment_exists(foreign)) << "not a valid Archet segment: not ours to judge";
    EXPECT_TRUE(segment_exists(ours.name())) << "its studio lives";
    EXPECT_TRUE(segment_exists(link.segment_name()));
    ::kill(engine, SIGKILL);
    ::waitpid(engine, nullptr, 0);
    for (const std::string& name : {stale, engine_lives, foreign}) ::shm_unlink(name.c_str());
}

// A model that no machine steps in real time (a hundred thousand masses at 192 kHz) is
// measured off the real-time path before it is swapped in, and refused with its cost and the
// budget; the shipped string is accepted at the same rate. (Nothing here depends on how fast
// the machine is: the heavy model is over ten times any budget, also in the sanitizers' builds
// after their slowdown is scaled back, and the light one far under it. With 30,000 masses, as
// once, the AddressSanitizer build scaled back by a guessed factor of 10 let it play.)
TEST(EngineProcess, RefusesAModelTooHeavyForRealTime) {
    Model heavy = load_model_file(test::resource("models/bowed-string-220.json"));
    heavy.name = "heavy";
    constexpr int kMasses = 100000;
    for (int i = 0; i < kMasses; ++i) {
        Mat m;
        m.id = "h" + std::to_string(i);
        m.kind = MatKind::Mass;
        m.mass = 1e-3;
        heavy.mats.push_back(m);
        if (i == 0) continue;
        Lia l;
        l.id = "hk" + std::to_string(i);
        l.kind = LiaKind::Spring;
        l.from = "h" + std::to_string(i - 1);
        l.to = m.id;
        l.stiffness = 1;
        heavy.lias.push_back(l);
    }
    const auto dir = test::temp_dir("engine-heavy");
    write_file_atomically(dir / "heavy.json", format_model(heavy));

    EngineLinkOptions o = options();
    o.sample_rate = 192000;
    EngineLink link(o);
    link.start();
    ASSERT_TRUE(
        wait_for([&] { return link.liveness() == EngineLink::Liveness::Running; }, kGenerous));
    std::vector<std::string> errors;
    const auto heavy_load = link.load_model((dir / "heavy.json").string());
    const auto answer = load_answer(link, heavy_load, errors, 120000ms);
    ASSERT_TRUE(answer.has_value()) << "no answer to the load";
    ASSERT_EQ(*answer, StatusKind::Error) << "the heavy model was accepted";
    const std::string said = errors.back();
    EXPECT_NE(said.find("cannot play in real time"), std::string::npos) << said;
    EXPECT_NE(said.find("ms per block of 64 frames, which lasts 0.333 ms"), std::string::npos)
        << said;
    EXPECT_NE(said.find("reduce the masses"), std::string::npos) << said;

    errors.clear();
    const auto light = link.load_model(test::resource("models/bowed-string-220.json").string());
    EXPECT_TRUE(wait_status(link, StatusKind::ModelLoaded, light, errors, kGenerous))
        << (errors.empty() ? "" : errors.back());
    EXPECT_EQ(link.liveness(), EngineLink::Liveness::Running);
}

}  // namespace
}  // namespace archet::ipc
