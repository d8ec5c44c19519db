// The OSC address space: every address acts with its arguments as sent in any numeric type,
// and anything else (unknown addresses, wrong argument types or counts, numbers out of range
// or not finite, names that are no ELEMENT.PARAM, bundles, bytes that are not OSC) is refused
// with a sentence that names the address and what to send. Packets are built with liblo, as
// the senders' libraries build them.

#include <gtest/gtest.h>
#include <lo/lo.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include "archet/engine/osc_packet.hpp"
#include "archet/ipc/osc_command.hpp"

namespace archet {
namespace {

using ipc::OscCommand;
using Kind = OscCommand::Kind;

// The packet liblo sends for `message` at `path`, decoded.
std::variant<OscCommand, std::string> send(const char* path, lo_message message) {
    std::size_t size = 0;
    void* bytes = lo_message_serialise(message, path, nullptr, &size);
    auto decoded = decode_osc_packet(static_cast<const std::uint8_t*>(bytes), size);
    std::free(bytes);
    lo_message_free(message);
    return decoded;
}

OscCommand accepted(const std::variant<OscCommand, std::string>& d) {
    if (const auto* why = std::get_if<std::string>(&d)) ADD_FAILURE() << *why;
    return std::get_if<OscCommand>(&d) ? std::get<OscCommand>(d) : OscCommand{};
}

std::string refused(const std::variant<OscCommand, std::string>& d) {
    if (std::holds_alternative<OscCommand>(d)) ADD_FAILURE() << "accepted";
    return std::get_if<std::string>(&d) ? std::get<std::string>(d) : "";
}

lo_message with_float(float v) {
    lo_message m = lo_message_new();
    lo_message_add_float(m, v);
    return m;
}

TEST(Osc, EachAddressActsWithItsArguments) {
    const OscCommand slide = accepted(send("/archet/bow/slide", with_float(0.05f)));
    EXPECT_EQ(slide.kind, Kind::Slide);
    EXPECT_DOUBLE_EQ(slide.value, 0.05f);
    lo_message press = lo_message_new();
    lo_message_add_double(press, 0.0015);
    EXPECT_EQ(accepted(send("/archet/bow/press", press)).value, 0.0015) << "a double";
    lo_message finger = lo_message_new();
    lo_message_add_int32(finger, 1);
    const OscCommand f = accepted(send("/archet/finger", finger));
    EXPECT_EQ(f.kind, Kind::Finger);
    EXPECT_EQ(f.value, 1.0) << "an int32";
    lo_message pressure = lo_message_new();
    lo_message_add_int64(pressure, 0);
    EXPECT_EQ(accepted(send("/archet/finger/pressure", pressure)).kind, Kind::FingerPressure);
    lo_message param = lo_message_new();
    lo_message_add_string(param, "friction.mu_s");
    lo_message_add_float(param, 0.7f);
    const OscCommand p = accepted(send("/archet/param", param));
    EXPECT_EQ(p.kind, Kind::Parameter);
    EXPECT_EQ(p.parameter, (ParameterName{"friction", "mu_s"}));
    EXPECT_NEAR(p.value, 0.7, 1e-7);
    for (const std::string word : {"start", "stop"}) {
        lo_message record = lo_message_new();
        lo_message_add_string(record, word.c_str());
        EXPECT_EQ(accepted(send("/archet/record", record)).kind,
                  word == "start" ? Kind::RecordStart : Kind::RecordStop);
    }
}

TEST(Osc, RefusesWhatItCannotActOnAndSaysWhatToSend) {
    const std::string unknown = refused(send("/archet/bow", with_float(1)));
    EXPECT_NE(unknown.find("unknown address \"/archet/bow\""), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("/archet/bow/slide f (m)"), std::string::npos) << "the space listed";
    EXPECT_NE(refused(send("/archet/finger", lo_message_new())).find("takes one number"),
              std::string::npos);
    lo_message two = with_float(0.5f);
    lo_message_add_float(two, 0.5f);
    EXPECT_NE(refused(send("/archet/finger", two)).find("not ,ff"), std::string::npos);
    EXPECT_NE(refused(send("/archet/finger", with_float(1.5f))).find("out of range; send 0 to 1"),
              std::string::npos);
    EXPECT_NE(refused(send("/archet/bow/press", with_float(2))).find("out of range"),
              std::string::npos);
    EXPECT_NE(
        refused(send("/archet/bow/slide", with_float(std::numeric_limits<float>::quiet_NaN())))
            .find("finite"),
        std::string::npos);
    lo_message unnamed = lo_message_new();
    lo_message_add_string(unnamed, "mu_s");
    lo_message_add_float(unnamed, 0.7f);
    EXPECT_NE(refused(send("/archet/param", unnamed)).find("ELEMENT.PARAMETER"), std::string::npos);
    lo_message record = lo_message_new();
    lo_message_add_string(record, "pause");
    EXPECT_NE(refused(send("/archet/record", record)).find("\"start\" or \"stop\""),
              std::string::npos);
    lo_message truth = lo_message_new();
    lo_message_add_true(truth);
    EXPECT_NE(refused(send("/archet/finger", truth)).find("not ,T"), std::string::npos);
}

TEST(Osc, RefusesBytesThatAreNoOscMessageAndQuotesControlCharacters) {
    const std::string junk = "not OSC at all";
    EXPECT_NE(
        refused(decode_osc_packet(reinterpret_cast<const std::uint8_t*>(junk.data()), junk.size()))
            .find("malformed"),
        std::string::npos);
    const std::uint8_t bundle[16] = {'#', 'b', 'u', 'n', 'd', 'l', 'e', 0};
    EXPECT_NE(refused(decode_osc_packet(bundle, sizeof bundle)).find("bundle"), std::string::npos);
    EXPECT_NE(refused(decode_osc_packet(bundle, 0)).find("0 bytes"), std::string::npos);
    const std::string said = refused(send("/archet/\x1b[31mred", with_float(1)));
    EXPECT_EQ(said.find('\x1b'), std::string::npos) << "no escape reaches a terminal";
    EXPECT_NE(said.find("\\x1b"), std::string::npos) << said;
}

}  // namespace
}  // namespace archet
