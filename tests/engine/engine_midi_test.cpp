// MIDI into a real engine process, from a JACK MIDI keyboard written here on a JACK server of
// the test's own (dummy driver): a note stops the fingered string at its pitch and bows it in
// Helmholtz motion, a take made from MIDI re-renders to the byte, thousands of controller
// messages cost the real-time thread no allocation, and a bad mapping file is refused before
// anything starts.

#include <gtest/gtest.h>

#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include <RtMidi.h>
#include <unistd.h>

#include "archet/analysis/bowing_analysis.hpp"
#include "archet/builders/bowed_string.hpp"
#include "archet/files/model_file.hpp"
#include "archet/files/take_file.hpp"
#include "engine_session.hpp"
#include "jack_dummy.hpp"
#include "jack_midi_keyboard.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

using ipc::StatusFrame;
using ipc::StatusKind;
using test::EngineSession;

class EngineMidi : public test::JackDummy {
  protected:
    static EngineSession::EngineLinkOptions with_midi() {
        auto o = EngineSession::options();
        o.midi = "virtual", o.midi_api = "jack";
        return o;
    }
    // The fingered paper string at 220 Hz (A3), the engine listening, the keyboard plugged in.
    void start() {
        dir_ = test::temp_dir("engine-midi");
        BowedStringOptions o;
        o.pitch = 220, o.paper = true, o.finger = true;
        write_file_atomically(dir_ / "fingered.json", format_model(build_bowed_string(o)));
        engine_ = std::make_unique<EngineSession>(with_midi());
        ASSERT_TRUE(engine_->start_file(dir_ / "fingered.json"));
        keyboard_ = std::make_unique<test::JackMidiKeyboard>();
        ASSERT_TRUE(test::wait_for([&] { return keyboard_->connect("archet"); }, test::kGenerous))
            << "the engine's MIDI input did not appear on JACK; errors: "
            << (engine_->errors().empty() ? "none" : engine_->errors().back());
    }
    // Plays on for `seconds` of sound.
    bool play(double seconds) {
        const auto until = engine_->played() + static_cast<std::uint64_t>(seconds * 48000);
        return engine_->play_until([&] { return engine_->played() >= until; }, [](double) {});
    }

    std::filesystem::path dir_;
    std::unique_ptr<EngineSession> engine_;
    std::unique_ptr<test::JackMidiKeyboard> keyboard_;
};

TEST_F(EngineMidi, ANoteIsBowedAtItsPitchAndItsTakeReRendersToTheByte) {
    ASSERT_NO_FATAL_FAILURE(start());
    const auto folder = dir_ / "take";
    engine_->link().start_take(folder.string());
    ASSERT_TRUE(engine_->await(StatusKind::Take, [&](const StatusFrame& f) {
        return std::string(f.text).rfind("recording ", 0) == 0;
    })) << (engine_->errors().empty() ? "" : engine_->errors().back());
    ASSERT_TRUE(keyboard_->note_on(64, 64));  // E4, a fifth above the open A3, mezzo forte
    ASSERT_TRUE(play(1.5));
    EXPECT_GT(engine_->latest().values[4], 0.01) << "the note pressed the bow in";
    ASSERT_TRUE(keyboard_->note_off(64));
    ASSERT_TRUE(play(0.3));
    EXPECT_LT(engine_->latest().values[4], 1e-9) << "its release lifted the bow";
    engine_->link().stop_take();
    std::string said;
    ASSERT_TRUE(engine_->await_take_written(&said)) << said;
    EXPECT_TRUE(engine_->errors().empty()) << engine_->errors().front();

    // Helmholtz motion at the stopped string's pitch, half a second from 0.8 s into the note.
    const std::vector<double> slip = test::probe_column(folder / "probes.csv", "slip_v");
    const std::vector<double> normal = test::probe_column(folder / "probes.csv", "normal_force");
    std::size_t first = 0;
    while (first < normal.size() && normal[first] <= 0) ++first;
    ASSERT_GT(normal.size(), first + 62400) << "the note was recorded for 1.3 s";
    const double fifth = 220 * std::pow(2.0, 7.0 / 12);
    const BowingAnalysis a = analyse_bowing(slip, 48000, fifth, first + 38400, first + 62400);
    EXPECT_TRUE(a.helmholtz()) << a.slips_per_period << " slips a period, spread "
                               << a.period_spread;
    EXPECT_LT(std::abs(a.pitch_cents), 15) << a.pitch_cents << " cents against E4";

    const auto r = test::run_archet(
        {"render", "--take", folder.string(), "-o", (dir_ / "again.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(test::read_file(dir_ / "again.wav"), test::read_file(folder / "take.wav"))
        << "the take made from MIDI re-renders to the byte";
}

TEST_F(EngineMidi, ThousandsOfControllerMessagesCostTheRealTimeThreadNoAllocation) {
    ASSERT_NO_FATAL_FAILURE(start());
    ASSERT_TRUE(keyboard_->note_on(69, 90));
    for (int i = 0; i < 5000; ++i) {
        // Faster than any controller (200 messages a millisecond), not faster than the
        // engine's queue can hold between two rounds.
        if (i % 400 == 0) {
            ASSERT_TRUE(play(0.002));
        }
        ASSERT_TRUE(keyboard_->control(2, 20 + i % 60));  // bow force
        if (i % 10 == 0) keyboard_->send({0xE0, 0, static_cast<std::uint8_t>(64 + i % 8)});
        if (i % 100 == 0) keyboard_->control(1, i % 128);  // vibrato depth
    }
    ASSERT_TRUE(play(0.25));
    // The force swept by every message kicks the bow's pressure mass, which may leave the string
    // for a moment; over the last quarter second it is back on.
    double pressed = 0;
    const auto until = engine_->played() + 12000;
    ASSERT_TRUE(engine_->play_until(
        [&] { return engine_->played() >= until; },
        [&](double) { pressed = std::max(pressed, engine_->latest().values[4]); }));
    ASSERT_TRUE(engine_->await(StatusKind::Heartbeat, [](const StatusFrame&) { return true; }));
    EXPECT_EQ(engine_->realtime_allocations(), 0u);
    EXPECT_GT(pressed, 0.01) << "still bowing";
    EXPECT_TRUE(engine_->errors().empty()) << engine_->errors().front();
}

TEST_F(EngineMidi, ANoteOutOfReachIsSaidAndChangesNothing) {
    ASSERT_NO_FATAL_FAILURE(start());
    ASSERT_TRUE(keyboard_->note_on(40, 100));  // E2, below the open A3
    ASSERT_TRUE(engine_->await(StatusKind::Error, [](const StatusFrame&) { return true; }));
    EXPECT_NE(engine_->errors().back().find("note 40"), std::string::npos)
        << engine_->errors().back();
    ASSERT_TRUE(play(0.2));
    EXPECT_LT(engine_->latest().values[4], 1e-9) << "the bow stayed off the string";
}

// STK's CC 4 moves the bow along the string while it plays and a take records: the model with
// its bow elsewhere takes over the string's motion, so the sound (the bridge force) carries on
// instead of starting again from a string at rest, the bow stays on the string, and the take
// keeps the move and re-renders to the byte.
TEST_F(EngineMidi, TheBowMovesAlongTheStringWhileItPlays) {
    ASSERT_NO_FATAL_FAILURE(start());
    ASSERT_TRUE(keyboard_->note_on(57, 90));  // the open A3
    ASSERT_TRUE(play(1.0));
    // The bridge force, one sample a round (2 ms, at no particular phase): its RMS over 40 ms.
    auto loudness = [&] {
        double sum = 0;
        int n = 0;
        const auto until = engine_->played() + 1920;
        engine_->play_until([&] { return engine_->played() >= until; },
                            [&](double) {
                                const double f = engine_->latest().values[6];
                                sum += f * f, ++n;
                            });
        return n > 0 ? std::sqrt(sum / n) : 0.0;
    };
    engine_->link().start_take((dir_ / "take").string());
    ASSERT_TRUE(engine_->await(StatusKind::Take, [&](const StatusFrame& f) {
        return std::string(f.text).rfind("recording ", 0) == 0;
    }));
    const double before = loudness();
    ASSERT_GT(before, 0) << "the note sounds";
    const std::uint64_t tick = engine_->latest().tick;
    ASSERT_TRUE(keyboard_->control(4, 127));  // β = 0.3, from the model's 0.115
    ASSERT_TRUE(engine_->await(StatusKind::Heartbeat, [](const StatusFrame&) { return true; }));
    double quietest = before;
    for (int w = 0; w < 5; ++w) quietest = std::min(quietest, loudness());
    EXPECT_GT(quietest, 0.2 * before) << "the string played on through the move";
    engine_->link().stop_take();
    std::string said;
    ASSERT_TRUE(engine_->await_take_written(&said)) << said;
    const auto changes = read_parameter_changes(dir_ / "take" / "parameters.json");
    ASSERT_FALSE(changes.empty());
    EXPECT_EQ(changes.front().parameter, "bow.position") << "the take kept the move";
    const auto r = test::run_archet(
        {"render", "--take", (dir_ / "take").string(), "-o", (dir_ / "again.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(test::read_file(dir_ / "again.wav"), test::read_file(dir_ / "take" / "take.wav"))
        << "the take across the move re-renders to the byte";
    // The moved model took over the playing one's whole state, its clock included: a model
    // started afresh would count its ticks from 0.
    EXPECT_GT(engine_->latest().tick, tick) << "the string's motion was handed over";
    EXPECT_GT(engine_->latest().values[4], 0.01) << "still bowing";
    EXPECT_TRUE(engine_->errors().empty()) << engine_->errors().front();
}

// A model loaded while a note is held: the new model's performer holds no note, so the bow the
// old one drove is lifted rather than left bowing with no key down.
TEST_F(EngineMidi, ANewModelLiftsTheBowOfANoteHeldBeforeIt) {
    ASSERT_NO_FATAL_FAILURE(start());
    ASSERT_TRUE(keyboard_->note_on(57, 90));
    ASSERT_TRUE(play(0.5));
    ASSERT_GT(engine_->latest().values[4], 0.01) << "bowing";
    const auto loaded = engine_->link().load_model((dir_ / "fingered.json").string());
    ASSERT_TRUE(engine_->await(StatusKind::ModelLoaded,
                               [&](const StatusFrame& f) { return f.sequence == loaded; }));
    ASSERT_TRUE(play(0.5));
    EXPECT_LT(engine_->latest().values[4], 1e-9) << "the bow was lifted";
}

// The studio hears which controller moved (its MIDI learn assigns it), mapped or not.
TEST_F(EngineMidi, TheStudioIsToldWhichControllerMoved) {
    ASSERT_NO_FATAL_FAILURE(start());
    ASSERT_TRUE(keyboard_->control(74, 90));
    std::string said;
    ASSERT_TRUE(engine_->await(StatusKind::Midi, [&](const StatusFrame& f) {
        said = f.text;
        return f.sequence == 74;
    }));
    EXPECT_EQ(said, "CC 74 = 90 (channel 1)");
}

// `archet play --midi` without the studio: the engine it starts listens, a note played on the
// keyboard is in its take, and the take re-renders to the byte.
TEST_F(EngineMidi, PlayFromTheCommandLineRecordsWhatTheKeyboardPlays) {
    const auto dir = test::temp_dir("play-midi");
    BowedStringOptions o;
    o.pitch = 220, o.paper = true, o.finger = true;
    write_file_atomically(dir / "fingered.json", format_model(build_bowed_string(o)));
    const auto take = dir / "take";
    std::vector<std::string> args{ARCHET_BINARY, "play",    (dir / "fingered.json").string(),
                                  "--midi",      "virtual", "--midi-api",
                                  "jack",        "--take",  take.string(),
                                  "--duration",  "4"};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = -1;
    ASSERT_EQ(::posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ), 0);
    test::JackMidiKeyboard keyboard;
    ASSERT_TRUE(test::wait_for([&] { return keyboard.connect("archet"); }, test::kGenerous));
    ASSERT_TRUE(test::wait_for([&] { return std::filesystem::exists(take / "take.wav"); },
                               test::kGenerous));
    ASSERT_TRUE(keyboard.note_on(64, 64));
    int status = -1;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
    const std::vector<double> normal = test::probe_column(take / "probes.csv", "normal_force");
    EXPECT_GT(*std::max_element(normal.begin(), normal.end()), 0.05) << "the note bowed";
    const auto r =
        test::run_archet({"render", "--take", take.string(), "-o", (dir / "again.wav").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(test::read_file(dir / "again.wav"), test::read_file(take / "take.wav"));
}

// The ALSA sequencer, where most desktop controllers appear: a program's output port (RtMidi's,
// as a sequencer's would be) connected to the engine's archet-midi:midi_in plays a note. Skips
// where the machine has no sequencer (a container without /dev/snd/seq).
TEST(EngineMidiAlsa, ANoteFromTheSequencerIsBowed) {
    if (::access("/dev/snd/seq", R_OK | W_OK) != 0)
        GTEST_SKIP() << "no ALSA sequencer on this machine (/dev/snd/seq; modprobe snd-seq)";
    const auto dir = test::temp_dir("engine-midi-alsa");
    BowedStringOptions o;
    o.pitch = 220, o.paper = true, o.finger = true;
    write_file_atomically(dir / "fingered.json", format_model(build_bowed_string(o)));
    auto options = EngineSession::options();
    options.midi = "virtual", options.midi_api = "alsa";
    EngineSession engine(options);
    ASSERT_TRUE(engine.start_file(dir / "fingered.json"));
    RtMidiOut out(RtMidi::LINUX_ALSA, "keyboard");
    unsigned port = 0;
    ASSERT_TRUE(test::wait_for(
        [&] {
            for (port = 0; port < out.getPortCount(); ++port)
                if (out.getPortName(port).find("archet") != std::string::npos) return true;
            return false;
        },
        test::kGenerous))
        << "the engine's port did not appear on the sequencer";
    out.openPort(port);
    const std::vector<unsigned char> note{0x90, 64, 64};
    out.sendMessage(&note);
    const auto until = engine.played() + 24000;
    ASSERT_TRUE(engine.play_until([&] { return engine.played() >= until; }, [](double) {}));
    EXPECT_GT(engine.latest().values[4], 0.01) << "the note pressed the bow in";
    EXPECT_TRUE(engine.errors().empty()) << engine.errors().front();
}

TEST(EngineMidiOptions, ABadMappingFileIsRefusedBeforeAnythingStarts) {
    const auto dir = test::temp_dir("engine-midi-map");
    const auto map = dir / "map.json";
    std::ofstream(map) << R"({"format": "archet-midi-map", "controls": [
        {"controller": 2, "target": "bow_presure", "range": [0, 1]}]})";
    const auto r =
        test::run_archet({"engine", "--shm", "/archet-none", "--midi", "--midi-map", map.string()});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("controls[0].target"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("bow_force"), std::string::npos) << r.err;
    const std::string model = test::resource("models/bowed-string-220.json").string();
    const auto play = test::run_archet({"play", model, "--midi", "--midi-map", map.string()});
    EXPECT_EQ(play.status, 2);
    EXPECT_NE(play.err.find("controls[0].target"), std::string::npos) << play.err;
    const auto both = test::run_archet({"play", model, "--osc", "9000", "--gesture", model});
    EXPECT_EQ(both.status, 2);
    EXPECT_NE(both.err.find("--gesture"), std::string::npos) << both.err;
}

}  // namespace
}  // namespace archet
