// The engine's command decoder: frames as another process could write them. Garbage is
// refused with a reason; good frames decode to what was sent. And the take folders a command
// may name: only inside the take directory.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <set>
#include <string>
#include <variant>

#include "archet/common/input_error.hpp"
#include "archet/common/printable_text.hpp"
#include "archet/ipc/command_decoder.hpp"
#include "archet/ipc/take_folder.hpp"
#include "test_support.hpp"

namespace archet::ipc {
namespace {

CommandFrame frame(Opcode op, const char* text = "", double value = 0) {
    CommandFrame f{};
    f.opcode = static_cast<std::uint32_t>(op);
    f.sequence = 7;
    f.value = value;
    std::strncpy(f.text, text, kTextSize - 1);
    return f;
}

std::string refusal(const CommandFrame& f) {
    const auto d = decode_command(f);
    return std::holds_alternative<std::string>(d) ? std::get<std::string>(d) : "";
}

TEST(CommandDecoder, DecodesWhatWasSent) {
    const auto d = decode_command(frame(Opcode::SetParameter, "friction.mu_s", 0.7));
    ASSERT_TRUE(std::holds_alternative<DecodedCommand>(d));
    const auto& c = std::get<DecodedCommand>(d);
    EXPECT_EQ(c.opcode, Opcode::SetParameter);
    EXPECT_EQ(c.text, "friction.mu_s");
    EXPECT_EQ(c.parameter, (ParameterName{"friction", "mu_s"}));
    EXPECT_EQ(c.value, 0.7);
    EXPECT_EQ(c.sequence, 7u);
}

// Every opcode the decoder accepts has a name of its own for logs, and no other value has one:
// a frame's opcode field may hold anything, and that is "unknown".
TEST(CommandDecoder, EveryOpcodeHasItsOwnName) {
    std::set<std::string> names;
    for (std::uint32_t raw = 0; raw < 1024; ++raw) {
        CommandFrame f = frame(Opcode::Play, "a.b", 1);  // a text and value every opcode takes
        f.opcode = raw;
        const bool known = std::holds_alternative<DecodedCommand>(decode_command(f));
        const std::string name = opcode_name(raw);
        ASSERT_FALSE(name.empty()) << raw;
        if (!known) {
            EXPECT_EQ(name, "unknown") << raw;
            continue;
        }
        EXPECT_NE(name, "unknown") << raw;
        EXPECT_TRUE(names.insert(name).second) << name << " names two opcodes";
    }
    EXPECT_EQ(names.size(), 8u) << "LoadModel to StopTake";
    EXPECT_STREQ(opcode_name(Opcode::SetParameter), "SetParameter");
}

TEST(CommandDecoder, EveryStatusKindHasItsOwnName) {
    std::set<std::string> names;
    for (const StatusKind kind : {StatusKind::Heartbeat, StatusKind::ModelLoaded, StatusKind::Error,
                                  StatusKind::Blowup, StatusKind::Take}) {
        const std::string name = status_kind_name(kind);
        EXPECT_FALSE(name.empty());
        EXPECT_NE(name, "unknown");
        EXPECT_TRUE(names.insert(name).second) << name << " names two kinds";
        EXPECT_EQ(name, status_kind_name(static_cast<std::uint32_t>(kind)));
    }
    EXPECT_STREQ(status_kind_name(std::uint32_t{0}), "unknown");
    EXPECT_STREQ(status_kind_name(std::uint32_t{99}), "unknown");
}

TEST(CommandDecoder, RefusesGarbageWithAReason) {
    CommandFrame unterminated = frame(Opcode::LoadModel);
    std::memset(unterminated.text, 'x', kTextSize);
    EXPECT_EQ(refusal(unterminated), "command text is not NUL-terminated");
    CommandFrame unknown = frame(Opcode::Play);
    unknown.opcode = 99;
    EXPECT_EQ(refusal(unknown), "unknown opcode 99");
    EXPECT_EQ(refusal(frame(Opcode::LoadModel, "")), "LoadModel needs a path");
    EXPECT_EQ(refusal(frame(Opcode::StartTake, "")), "StartTake needs a path");
    EXPECT_NE(refusal(frame(Opcode::SetParameter, "mu_s", 1)).find("ELEMENT.PARAMETER"),
              std::string::npos);
    EXPECT_NE(refusal(frame(Opcode::SetParameter, "friction.", 1)).find("ELEMENT.PARAMETER"),
              std::string::npos);
    EXPECT_NE(refusal(frame(Opcode::SetParameter, "a.b", std::nan(""))).find("finite"),
              std::string::npos);
    CommandFrame far = frame(Opcode::Gesture);
    far.slide = 1e300;
    EXPECT_NE(refusal(far).find("within ±100 m"), std::string::npos);
    far.slide = 0, far.press = -std::numeric_limits<double>::infinity();
    EXPECT_NE(refusal(far).find("finite"), std::string::npos);
}

std::string take_refusal(const std::string& folder, const std::filesystem::path& root) {
    try {
        check_take_folder(folder, root);
        return "";
    } catch (const InputError& e) {
        return e.what();
    }
}

TEST(TakeFolder, OnlyPlainPrintablePathsInsideTheTakeDirectory) {
    const auto dir = test::temp_dir("take-folder");
    const auto root = prepare_take_directory((dir / "takes").string());
    EXPECT_TRUE(std::filesystem::is_directory(root)) << "made when missing";
    std::filesystem::create_directory_symlink(dir, root / "up");
    EXPECT_EQ(take_refusal((root / "2026-12-01").string(), root), "");
    EXPECT_EQ(take_refusal((root / "Caf\xc3\xa9" / "take").string(), root), "")
        << "a UTF-8 name is printable";
    EXPECT_NE(take_refusal("take", root).find("is relative"), std::string::npos);
    EXPECT_NE(take_refusal((root / "a" / ".." / ".." / "b").string(), root).find("\"..\""),
              std::string::npos);
    EXPECT_NE(take_refusal((root / "up" / "b").string(), root).find("not inside"),
              std::string::npos)
        << "a symbolic link out of it";
    EXPECT_NE(take_refusal(root.string(), root).find("not inside"), std::string::npos)
        << "the directory itself is not a take";
    EXPECT_NE(take_refusal((dir / "takes-other").string(), root).find("not inside"),
              std::string::npos)
        << "a sibling whose name starts like it";
    const std::string binary = take_refusal((root / "\x01\xff\n").string(), root);
    EXPECT_NE(binary.find("\\x01\\xff\\x0a"), std::string::npos) << binary;
    EXPECT_NE(binary.find("non-printable"), std::string::npos) << binary;
    EXPECT_NE(take_refusal((root / "\xc0\xaf").string(), root).find("non-printable"),
              std::string::npos)
        << "an overlong UTF-8 /";
    EXPECT_NE(take_refusal((root / "x").string(), "").find("--takes"), std::string::npos)
        << "an engine without a take directory records nothing";
    EXPECT_EQ(quoted_text(std::string(200, 'a'), 8), "\"aaaaaaaa...\"");
}

}  // namespace
}  // namespace archet::ipc
