// A corpus of bad models, gestures and command lines, run through the real `archet`: each
// gets a message naming the element and the fix, exit status 2, and no file of the user's is
// touched.

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "test_support.hpp"

namespace archet {
namespace {

struct Case {
    std::string file, expected;
};

std::vector<Case> corpus(const std::string& folder) {
    std::vector<Case> cases;
    std::istringstream lines(test::read_file(test::test_data(folder + "/expected.txt")));
    std::string line;
    while (std::getline(lines, line)) {
        const auto tab = line.find('\t');
        if (tab != std::string::npos) cases.push_back({line.substr(0, tab), line.substr(tab + 1)});
    }
    return cases;
}

TEST(BadInput, EveryBadModelIsRefusedWithAClearMessageAndStatus2) {
    const auto cases = corpus("bad-models");
    ASSERT_GE(cases.size(), 20u);
    const auto dir = test::temp_dir("bad-models");
    const auto precious = dir / "precious.wav";
    for (const auto& c : cases) {
        SCOPED_TRACE(c.file);
        const std::string model = test::test_data("bad-models/" + c.file).string();
        const auto check = test::run_archet({"check", model});
        EXPECT_EQ(check.status, 2);
        EXPECT_NE((check.out + check.err).find(c.expected), std::string::npos)
            << check.out << check.err;
        EXPECT_EQ((check.out + check.err).find('\x1b'), std::string::npos)
            << "a control character reached the terminal";

        // Rendering it over an existing file leaves that file exactly as it was.
        { std::ofstream(precious) << "the user's earlier take"; }
        const auto render = test::run_archet({"render", model, "-o", precious.string()});
        EXPECT_EQ(render.status, 2);
        EXPECT_NE(render.err.find(c.expected), std::string::npos) << render.err;
        EXPECT_EQ(test::read_file(precious), "the user's earlier take");
        EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1)
            << "no temporary left behind";
    }
}

TEST(BadInput, EveryBadGestureIsRefused) {
    const std::string model = test::resource("models/bowed-string-220.json").string();
    const auto dir = test::temp_dir("bad-gestures");
    for (const auto& c : corpus("bad-gestures")) {
        SCOPED_TRACE(c.file);
        const auto r = test::run_archet({"render", model, "--gesture",
                                         test::test_data("bad-gestures/" + c.file).string(), "-o",
                                         (dir / "out.wav").string()});
        EXPECT_EQ(r.status, 2);
        EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "out.wav"));
    }
}

// "0.001,0.002,…": n values.
std::string many_values(int n) {
    std::string list;
    for (int i = 1; i <= n; ++i) list += (i > 1 ? "," : "") + std::to_string(0.001 * i);
    return list;
}

TEST(BadInput, BadCommandLinesAreRefusedWithStatus2) {
    const std::string model = test::resource("models/bowed-string-220.json").string();
    const auto dir = test::temp_dir("bad-commands");
    const std::string out = (dir / "x.wav").string();
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"render", model, "-o", out, "--set", "s3.mas=1"}, "has no parameter \"mas\""},
        {{"render", model, "-o", out, "--set", "nothing.mass=1"}, "no mass or link has this id"},
        {{"render", model, "-o", out, "--set", "s3.mass=-2"},
         "s3.mass: must be above 0 kg (is -2)"},
        {{"render", model, "-o", out, "--set", "s3.mass"}, "expected ID.PARAM=VALUE"},
        {{"render", model, "-o", out, "--set", "k3.stiffness=1e12"}, "unstable"},
        {{"render", model, "-o", out, "--format", "mp3"}, "use wav or flac"},
        {{"render", model, "-o", out, "--duration", "-1"}, "--duration"},
        {{"render", model, "-o", (dir / "no/such/folder/x.wav").string()},
         "is the folder writable"},
        {{"render", (dir / "missing.json").string(), "-o", out}, "cannot open the file"},
        {{"render", model}, "--output is required"},
        {{"new", "bowed-string", "--pitch", "2000", "--paper", "-o", out}, "at most 11 masses"},
        {{"new", "bowed-string", "--pitch", "440", "--masses", "54", "-o", out},
         "at most 53 masses"},
        {{"new", "bowed-string", "--paper", "--masses", "80", "-o", out}, "25 to 60"},
        {{"new", "bowed-string", "--paper", "--body", "violin", "-o", out}, "have no body"},
        {{"new", "bowed-string", "--body", "theorbo", "-o", out}, "known bodies: violin"},
        {{"new", "bowed-string", "--point-bow", "-o", out},
         "build it without a stroke (--no-gesture)"},
        {{"new", "bowed-string", "--string-t60", "2", "--string-t60-high", "9", "-o", out},
         "--string-t60-high: must be at most"},
        {{"new", "bowed-string", "--pitch", "440", "--masses", "60", "-o", out},
         "60 masses at 440 Hz are unstable"},
        {{"new", "bowed-string", "--pitch", "-5", "-o", out}, "--pitch"},
        {{"new", "bowed-string", "--bow-position", "0.7", "-o", out}, "beta must be in (0, 0.5)"},
        {{"bench"}, "give either a MODEL file or --chain N"},
        {{"bench", model, "--chain-build", "sse9"}, "is fastest, avx512, avx2 or plain, not sse9"},
        {{"frobnicate"}, "subcommand"},
        // Output where nothing can be written: under a plain file, or in /proc (even as root).
        {{"render", model, "-o", (dir / "plain.txt" / "x.wav").string()}, "Not a directory"},
        {{"render", model, "-o", "/proc/archet-test.wav"}, "is the folder writable"},
        // Inputs and devices that do not exist.
        {{"render", "--take", (dir / "no-take").string(), "-o", out}, "cannot open the file"},
        {{"render", model, "--gesture", (dir / "none.json").string(), "-o", out},
         "cannot open the file"},
        {{"play", model, "--haptic", "evdev:/dev/input/no-such-event", "--duration", "0.1"},
         "cannot open the device"},
        {{"play", model, "--haptic", "sdl:42", "--duration", "0.1"}, "there is no joystick 42"},
        {{"map", model, "--force", "1:0.1:3", "-o", (dir / "map.csv").string()},
         "expected 0 < MIN ≤ MAX"},
        {{"map", model, "--position", "0.1:0.7:3", "-o", (dir / "map.csv").string()}, "MAX < 0.5"},
        {{"map", model, "--force", "abc", "-o", (dir / "map.csv").string()},
         "expected MIN:MAX:STEPS"},
        {{"map", model, "--shard", "3/2", "-o", (dir / "map.csv").string()}, "0 ≤ I < N"},
        // Told before its modes are analysed, and in those words.
        {{"map", test::test_data("no-bow.json").string(), "-o", (dir / "map.csv").string()},
         "plucked, not bowed: has no bow module (bow_friction) to map"},
        {{"map", "merge", (dir / "none.csv").string(), "--model", model, "-o",
          (dir / "map.csv").string()},
         "cannot open the file"},
        {{"compare", model, "--vary", "string.damping=1,2", "--gesture",
          (dir / "none.json").string(), "-o", (dir / "cmp").string()},
         "cannot open the file"},
        // Values that used to fall back to defaults silently, or run without end.
        {{"render", model, "-o", out, "--sample-rate", "nan"}, "must be from 1000 to 1e+06 Hz"},
        {{"render", model, "-o", out, "--sample-rate", "0"}, "must be from 1000 to 1e+06 Hz"},
        {{"check", model, "--sample-rate", "inf"}, "must be from 1000 to 1e+06 Hz"},
        {{"play", model, "--audio", "null", "--rate", "nan"}, "must be from 1000 to 1e+06 Hz"},
        {{"new", "bowed-string", "--sample-rate", "0", "-o", out}, "must be from 1000"},
        {{"render", model, "-o", out, "--duration", "0"}, "--duration: must be above 0 s"},
        {{"render", model, "-o", out, "--duration", "nan"}, "--duration: must be above 0 s"},
        {{"render", model, "-o", out, "--duration", "1e308"}, "raise --max-duration"},
        {{"play", model, "--audio", "null", "--duration", "1e308"}, "at most 3600 s"},
        {{"map", model, "--force", "0.1:1:100000000", "-o", (dir / "map.csv").string()},
         "more than --max-points 100000"},
        {{"compare", model, "--vary", "string.damping=" + many_values(65), "-o",
          (dir / "cmp").string()},
         "give at most 64 values to compare"},
        {{"compare", model, "--vary", "string.damping=1,2", "--jobs", "-1", "-o",
          (dir / "cmp").string()},
         "--jobs"},
        // Inputs that never end: read up to the bound, then refused.
        {{"check", "/dev/zero"}, "is larger than 64 MiB"},
        {{"render", "/dev/urandom", "-o", out}, "is larger than 64 MiB"},
        {{"render", model, "--gesture", "/dev/zero", "-o", out}, "is larger than 64 MiB"},
        {{"check", dir.string()}, "is a folder"},
        // Outputs that are not files.
        {{"render", model, "-o", dir.string()}, "is a folder; give a file name inside it"},
        {{"examples", "-o", (dir / "plain.txt").string()}, "is a file, not a folder"},
    };
    { std::ofstream(dir / "plain.txt") << "a file, not a folder"; }
    for (const auto& [arguments, expected] : cases) {
        SCOPED_TRACE(arguments[0] + " " + expected);
        const auto r = test::run_archet(arguments);
        EXPECT_EQ(r.status, 2);
        EXPECT_NE((r.err + r.out).find(expected), std::string::npos) << r.err << r.out;
    }
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_FALSE(std::filesystem::exists(dir / "cmp")) << "nothing written for a refused compare";
    EXPECT_FALSE(std::filesystem::exists(dir / "map.csv")) << "nor for a refused map";
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "plain.txt"));
}

// `-o` onto something that is not a regular file: a device or a FIFO is written in place and
// stays what it was (renaming a temporary over it turned /dev/full into a plain file).
TEST(BadInput, OutputOntoADeviceOrAFifoLeavesItADeviceOrAFifo) {
    const auto dir = test::temp_dir("special-outputs");
    const std::string model = test::resource("models/bowed-string-220.json").string();
    const auto fifo = dir / "pipe";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // A reader at the other end, as `archet render -o pipe | …` would have.
    auto through_pipe = [&](const std::vector<std::string>& arguments) {
        std::FILE* reader = ::popen(("cat " + fifo.string() + " > /dev/null").c_str(), "r");
        EXPECT_NE(reader, nullptr);
        const auto r = test::run_archet(arguments);
        if (reader) ::pclose(reader);
        return r;
    };
    const auto piped = through_pipe(
        {"render", model, "--format", "flac", "--duration", "0.1", "-o", fifo.string()});
    EXPECT_TRUE(std::filesystem::is_fifo(fifo)) << piped.err;
    const auto saved = through_pipe({"new", "bowed-string", "-o", fifo.string()});
    EXPECT_EQ(saved.status, 0) << saved.err;
    EXPECT_TRUE(std::filesystem::is_fifo(fifo));

    if (::geteuid() != 0) GTEST_SKIP() << "device nodes need root to create (mknod)";
    const auto full = dir / "full", null = dir / "null";
    ASSERT_EQ(::mknod(full.c_str(), S_IFCHR | 0666, ::makedev(1, 7)), 0);
    ASSERT_EQ(::mknod(null.c_str(), S_IFCHR | 0666, ::makedev(1, 3)), 0);
    const auto to_full =
        test::run_archet({"render", model, "--duration", "0.1", "-o", full.string()});
    EXPECT_EQ(to_full.status, 2) << to_full.err;
    EXPECT_NE(to_full.err.find("No space left on device"), std::string::npos) << to_full.err;
    EXPECT_TRUE(std::filesystem::is_character_file(full));
    const auto to_null =
        test::run_archet({"render", model, "--duration", "0.1", "-o", null.string()});
    EXPECT_EQ(to_null.status, 0) << to_null.err;
    EXPECT_TRUE(std::filesystem::is_character_file(null));
    const auto model_to_null = test::run_archet({"new", "bowed-string", "-o", null.string()});
    EXPECT_EQ(model_to_null.status, 0) << model_to_null.err;
    EXPECT_TRUE(std::filesystem::is_character_file(null));
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++entries;
    EXPECT_EQ(entries, 3u) << "no temporary file left beside them";
}

// A disk that fills up mid-write: a 64 kB tmpfs (mounting needs root; skipped otherwise).
TEST(BadInput, AFullDiskLeavesTheUsersFileWhole) {
    const auto dir = test::temp_dir("full-disk");
    const auto small = dir / "small";
    std::filesystem::create_directories(small);
    if (std::system(
            ("mount -t tmpfs -o size=64k tmpfs " + small.string() + " 2>/dev/null").c_str()) != 0)
        GTEST_SKIP() << "cannot mount a small tmpfs here (needs root)";
    { std::ofstream(small / "take.wav") << "the user's take"; }
    const auto r =
        test::run_archet({"render", test::resource("models/bowed-string-220.json").string(), "-o",
                          (small / "take.wav").string()});
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("the existing file is untouched"), std::string::npos) << r.err;
    EXPECT_EQ(test::read_file(small / "take.wav"), "the user's take");
    int files = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(small)) ++files;
    EXPECT_EQ(files, 1) << "no half-written temporary file left behind";
    std::system(("umount " + small.string()).c_str());
}

}  // namespace
}  // namespace archet
