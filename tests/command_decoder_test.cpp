// The engine's command decoder: frames as another process could write them. Garbage is
// refused with a reason; good frames decode to what was sent.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <variant>

#include "archet/ipc/command_decoder.hpp"

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
    EXPECT_EQ(c.value, 0.7);
    EXPECT_EQ(c.sequence, 7u);
}

TEST(CommandDecoder, RefusesGarbageWithAReason) {
    CommandFrame unterminated = frame(Opcode::LoadModel);
    std::memset(unterminated.text, 'x', kTextSize);
    EXPECT_EQ(refusal(unterminated), "command text is not NUL-terminated");
    CommandFrame unknown = frame(Opcode::Play);
    unknown.opcode = 99;
    EXPECT_EQ(refusal(unknown), "unknown opcode 99");
    EXPECT_NE(refusal(frame(Opcode::LoadModel, "")).find("needs a path"), std::string::npos);
    EXPECT_NE(refusal(frame(Opcode::StartTake, "")).find("needs a path"), std::string::npos);
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

}  // namespace
}  // namespace archet::ipc
