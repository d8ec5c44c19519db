// The .deb: CPack builds it from this build, it unpacks into a temporary root, and the
// installed `archet` answers --version, renders a shipped model, and finds the shipped models
// and gestures beside itself (share/archet) for the sound examples. The desktop entry, icon,
// AppStream metainfo and man page are in it.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "test_support.hpp"

namespace archet {
namespace {

int run(const std::string& command) {
    return std::system((command + " > /dev/null 2>&1").c_str());
}

TEST(Package, InstallsAndRunsFromATemporaryRoot) {
    const auto dir = test::temp_dir("package");
    ASSERT_EQ(run(std::string(ARCHET_CPACK) + " -G DEB --config " ARCHET_CPACK_CONFIG " -B " +
                  dir.string()),
              0)
        << "cpack";
    std::filesystem::path deb;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().extension() == ".deb") deb = entry.path();
    ASSERT_FALSE(deb.empty()) << "no .deb in " << dir;
    const auto root = dir / "root";
    ASSERT_EQ(run("dpkg-deb -x " + deb.string() + " " + root.string()), 0);

    const auto bin = root / "usr" / "bin";
    auto r = test::run_command({(bin / "archet").string(), "--version"});
    EXPECT_EQ(r.status, 0);
    EXPECT_NE(r.out.find("archet 0."), std::string::npos) << r.out;
    const auto share = root / "usr" / "share";
    r = test::run_command({(bin / "archet").string(), "render",
                           (share / "archet/models/bowed-string-220.json").string(), "-o",
                           (dir / "render.wav").string()});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_GT(std::filesystem::file_size(dir / "render.wav"), 100000u);
    r = test::run_command(
        {(bin / "archet").string(), "examples", "-o", (dir / "examples").string()});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "examples/sound-3-220Hz-detache.wav"))
        << "the installed binary found its models and gestures in share/archet";
    EXPECT_TRUE(std::filesystem::exists(bin / "archet-studio"));
    for (const char* file :
         {"applications/archet-studio.desktop", "icons/hicolor/scalable/apps/archet-studio.svg",
          "metainfo/org.archet.Studio.metainfo.xml", "man/man1/archet.1",
          "doc/archet/user-guide.md", "doc/archet/images/studio-dark.png"})
        EXPECT_TRUE(std::filesystem::exists(share / file)) << file;
    // The LV2 instrument, where hosts look for it, and seen by lilv as they see it.
    const auto lv2 = root / "usr" / "lib" / "lv2" / "archet.lv2";
    for (const char* file : {"archet.so", "manifest.ttl", "archet.ttl", "default.json"})
        EXPECT_TRUE(std::filesystem::exists(lv2 / file)) << "lib/lv2/archet.lv2/" << file;
    EXPECT_TRUE(std::filesystem::exists(share / "archet/midi/stk-bowed.json"));
    if (run("command -v lv2info") == 0) {
        r = test::run_command({"env",
                               "LV2_PATH=" + (root / "usr/lib/lv2").string() + ":/usr/lib/lv2",
                               "lv2info", "urn:archet:bowed-string"});
        EXPECT_EQ(r.status, 0) << r.err;
        EXPECT_NE(r.out.find("Instrument Plugin"), std::string::npos) << r.out;
        EXPECT_NE(r.out.find((lv2 / "archet.so").string()), std::string::npos) << r.out;
    }
    if (run("command -v desktop-file-validate") == 0) {
        EXPECT_EQ(
            run("desktop-file-validate " + (share / "applications/archet-studio.desktop").string()),
            0);
    }
    if (run("command -v man") == 0) {
        EXPECT_EQ(run("man -l " + (share / "man/man1/archet.1").string() + " | grep -q compare"),
                  0);
    }
}

// The set-up script of the README's two commands: its one option adds the peers the
// bench-peers target times Archet against; anything else is refused before apt is touched.
TEST(Package, TheSetUpScriptTakesItsOneOptionAndRefusesOthers) {
    const std::string script = ARCHET_SOURCE_DIR "/packaging/install-dependencies.sh";
    auto r = test::run_command({"bash", script, "--help"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("--peers"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("faust and libstk-dev"), std::string::npos) << r.out;
    r = test::run_command({"bash", script, "--peer"});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("unknown option '--peer'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--peers"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "") << "nothing installed";
}

}  // namespace
}  // namespace archet
