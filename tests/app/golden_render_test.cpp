// Byte-identical output across refactors: renders, probes, written models and a take re-render
// are compared, by a 64-bit FNV-1a digest of the whole file, against fixtures made by the code
// before the house was rebuilt (tests/data/golden/renders.json, commit recorded in the file).
//
// A change that alters the scheme's arithmetic on purpose regenerates the fixtures with
//   ARCHET_WRITE_GOLDEN=1 build/bin/golden_render_test
// and says why in its commit; nothing else may change these bytes.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace archet {
namespace {

const std::filesystem::path kFixtures = test::test_data("golden/renders.json");

std::string digest_of(const std::filesystem::path& file) {
    std::uint64_t hash = 1469598103934665603ull;
    for (const unsigned char byte : test::read_file(file)) {
        hash ^= byte;
        hash *= 1099511628211ull;
    }
    std::ostringstream text;
    text << std::hex << std::setw(16) << std::setfill('0') << hash;
    return text.str();
}

struct GoldenCase {
    std::string name;
    std::vector<std::string> arguments;  ///< "{out}" is the output file, "{res}" resources/
    std::string output = "out.wav";
};

std::vector<GoldenCase> golden_cases() {
    std::vector<GoldenCase> cases;
    for (const char* pitch : {"110", "220", "440", "880"}) {
        for (const char* tuning : {"", "-harmonic"}) {
            const std::string model = std::string("bowed-string-") + pitch + tuning;
            cases.push_back(
                {"render " + model, {"render", "{res}models/" + model + ".json", "-o", "{out}"}});
        }
    }
    for (const char* gesture : {"crescendo", "detache", "pressure-sweep", "steady-bow"}) {
        cases.push_back({std::string("gesture ") + gesture,
                         {"render", "{res}models/bowed-string-220.json", "--gesture",
                          std::string("{res}gestures/") + gesture + ".json", "-o", "{out}"}});
    }
    cases.push_back(
        {"set and flac",
         {"render", "{res}models/bowed-string-110.json", "--set", "friction.mu_s=0.9", "--set",
          "s3.mass=0.0003", "--format", "flac", "--duration", "1", "-o", "{out}"},
         "out.flac"});
    cases.push_back({"96 kHz",
                     {"render", "{res}models/bowed-string-440.json", "--sample-rate", "96000",
                      "--duration", "1", "-o", "{out}"}});
    cases.push_back({"probes",
                     {"render", "{res}models/bowed-string-220.json", "--duration", "0.1",
                      "--probes", "{out}", "-o", "{out}.wav"},
                     "probes.csv"});
    cases.push_back({"take re-render",
                     {"render", "--take", test::test_data("golden/take").string(), "-o", "{out}"}});
    // Played under scheme revision 3, before the friction solve took reciprocals (revision 4):
    // it re-renders with the divisions it was played with. Its probes show the friction to nine
    // digits, where the sound's 24 bits hide a last bit's difference for longer than the take.
    cases.push_back({"take re-render, revision 3",
                     {"render", "--take", test::test_data("golden/take-revision-3").string(),
                      "--probes", "{out}", "-o", "{out}.wav"},
                     "probes.csv"});
    cases.push_back(
        {"new chain", {"new", "bowed-string", "--pitch", "330", "-o", "{out}"}, "model.json"});
    cases.push_back({"new harmonic modal",
                     {"new", "bowed-string", "--pitch", "196", "--tuning", "harmonic",
                      "--structure", "modal", "--masses", "40", "-o", "{out}"},
                     "model.json"});
    return cases;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

/// Runs one case in a fresh folder and returns the digest of what it wrote.
std::string run_case(const GoldenCase& c, int index) {
    const auto dir = test::temp_dir("golden-" + std::to_string(index));
    const std::string out = (dir / c.output).string();
    std::vector<std::string> arguments;
    for (const auto& a : c.arguments)
        arguments.push_back(
            replaced(replaced(a, "{out}", out), "{res}", test::resource("").string()));
    const auto r = test::run_archet(arguments);
    EXPECT_EQ(r.status, 0) << c.name << ": " << r.err;
    const std::string digest = digest_of(out);
    std::filesystem::remove_all(dir);
    return digest;
}

TEST(GoldenRender, EveryRenderModelAndTakeIsByteIdenticalToTheFixtures) {
    const auto cases = golden_cases();
    if (std::getenv("ARCHET_WRITE_GOLDEN")) {
        nlohmann::ordered_json fixtures;
        for (std::size_t i = 0; i < cases.size(); ++i)
            fixtures[cases[i].name] = run_case(cases[i], static_cast<int>(i));
        std::ofstream(kFixtures) << fixtures.dump(2) << "\n";
        GTEST_SKIP() << "fixtures written to " << kFixtures;
    }
    const auto fixtures = nlohmann::json::parse(test::read_file(kFixtures));
    ASSERT_EQ(fixtures.size(), cases.size()) << "every case has a fixture and no fixture is stale";
    for (std::size_t i = 0; i < cases.size(); ++i) {
        ASSERT_TRUE(fixtures.contains(cases[i].name)) << cases[i].name;
        EXPECT_EQ(run_case(cases[i], static_cast<int>(i)),
                  fixtures[cases[i].name].get<std::string>())
            << cases[i].name << " no longer writes the same bytes";
    }
}

}  // namespace
}  // namespace archet
