// MIDI as a player sends it: the bytes of each message decoded (running status comes expanded
// from RtMidi; system messages play no part), the mapping file read and refused with the entry
// named, and the performer turning notes, the pitch wheel and controllers into the hand's
// motion and the finger's position.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "archet/midi/midi_mapping.hpp"
#include "archet/midi/midi_message.hpp"
#include "archet/midi/midi_performer.hpp"
#include "archet/realtime_allocations.hpp"
#include "test_support.hpp"

namespace archet::midi {
namespace {

using K = MidiMessage::Kind;

std::optional<MidiMessage> decode(std::vector<std::uint8_t> bytes) {
    return decode_midi(bytes);
}

TEST(MidiMessage, ChannelMessagesDecodeAndTheRestPlaysNoPart) {
    auto on = decode({0x93, 60, 100});
    ASSERT_TRUE(on);
    EXPECT_EQ(on->kind, K::NoteOn);
    EXPECT_EQ(on->channel, 4);
    EXPECT_EQ(on->number, 60);
    EXPECT_EQ(on->value, 100);
    EXPECT_EQ(decode({0x90, 60, 0})->kind, K::NoteOff) << "velocity 0 is a note-off";
    EXPECT_EQ(decode({0x80, 60, 64})->kind, K::NoteOff);
    auto cc = decode({0xBF, 2, 127});
    EXPECT_EQ(cc->kind, K::Control);
    EXPECT_EQ(cc->channel, 16);
    EXPECT_EQ(cc->number, 2);
    EXPECT_EQ(cc->value, 127);
    EXPECT_EQ(decode({0xE0, 0x00, 0x40})->value, 0) << "the wheel's centre";
    EXPECT_EQ(decode({0xE0, 0x7F, 0x7F})->value, 8191);
    EXPECT_EQ(decode({0xE0, 0x00, 0x00})->value, -8192);
    auto pressure = decode({0xD0, 90});
    EXPECT_EQ(pressure->kind, K::ChannelPressure);
    EXPECT_EQ(pressure->value, 90);
    EXPECT_EQ(describe(*on), "note on 60 velocity 100 (channel 4)");
    // Clock, sysex, program change, truncated and malformed messages: nothing.
    EXPECT_FALSE(decode({0xF8}));
    EXPECT_FALSE(decode({0xF0, 0x7E, 0xF7}));
    EXPECT_FALSE(decode({0xC0, 5}));
    EXPECT_FALSE(decode({0x90, 60}));
    EXPECT_FALSE(decode({0x90, 0x80, 1}));
    EXPECT_FALSE(decode({60, 100}));
    EXPECT_FALSE(decode({}));
}

TEST(MidiMapping, TheDefaultFollowsStksBowedAndIsTheShippedFile) {
    const MidiMapping m = default_midi_mapping();
    ASSERT_TRUE(m.route(2));
    EXPECT_EQ(m.route(2)->target, MidiTarget::BowForce);
    EXPECT_EQ(m.route(1)->target, MidiTarget::VibratoDepth);
    EXPECT_EQ(m.route(11)->target, MidiTarget::VibratoRate);
    EXPECT_EQ(m.route(kChannelPressure)->target, MidiTarget::BowSpeed);
    EXPECT_EQ(m.route(4)->target, MidiTarget::BowPosition);
    const std::string shipped = read_text_file(test::resource("midi/stk-bowed.json"));
    EXPECT_EQ(write_midi_mapping(m), shipped);
    EXPECT_EQ(write_midi_mapping(parse_midi_mapping(shipped, "stk-bowed.json")), shipped);
}

TEST(MidiMapping, AParameterRouteReadsBack) {
    const MidiMapping m = parse_midi_mapping(R"({"format": "archet-midi-map", "channel": 3,
        "controls": [{"controller": 74, "target": "parameter", "parameter": "friction.mu_s",
                      "range": [0.9, 0.5]}]})",
                                             "map.json");
    EXPECT_EQ(m.channel, 3);
    ASSERT_TRUE(m.route(74));
    EXPECT_EQ(m.route(74)->parameter.text(), "friction.mu_s");
    EXPECT_EQ(m.route(74)->minimum, 0.9) << "a controller may run backwards";
    EXPECT_EQ(parse_midi_mapping(write_midi_mapping(m), "again").route(74)->maximum, 0.5);
}

std::string refusal(const std::string& text) {
    try {
        parse_midi_mapping(text, "map.json");
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "accepted: " << text;
    return "";
}

TEST(MidiMapping, ABadFileNamesTheEntryAndWhatToChange) {
    const std::string head = R"({"format": "archet-midi-map", )";
    EXPECT_NE(refusal("{"), "");
    EXPECT_NE(refusal(R"({"format": "other"})").find("archet-midi-map"), std::string::npos);
    EXPECT_NE(refusal(head + R"("channel": 17})").find("map.json.channel"), std::string::npos);
    EXPECT_NE(refusal(head + R"("bend_range": -1})").find("bend_range"), std::string::npos);
    EXPECT_NE(refusal(head + R"("bow_speed": 0})").find("bow_speed"), std::string::npos);
    const std::string unknown =
        refusal(head + R"("controls": [{"controller": 2, "target": "bow_presure",
                                        "range": [0, 1]}]})");
    EXPECT_NE(unknown.find("map.json.controls[0].target"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("bow_force"), std::string::npos) << "lists the targets: " << unknown;
    const std::string twice = refusal(head + R"("controls": [
        {"controller": 2, "target": "bow_force", "range": [0, 1]},
        {"controller": 2, "target": "bow_speed", "range": [0, 1]}]})");
    EXPECT_NE(twice.find("controls[1].controller"), std::string::npos) << twice;
    const std::string far = refusal(
        head + R"("controls": [{"controller": 2, "target": "bow_force", "range": [0, 50]}]})");
    EXPECT_NE(far.find("0 to 5 N"), std::string::npos) << far;
    EXPECT_NE(refusal(head + R"("controls": [{"controller": 129, "target": "bow_force",
                                              "range": [0, 1]}]})")
                  .find("128 for channel pressure"),
              std::string::npos);
    EXPECT_NE(refusal(head + R"("controls": [{"controller": 7, "target": "parameter",
                                              "parameter": "nodot", "range": [0, 1]}]})")
                  .find("controls[0].parameter"),
              std::string::npos);
    EXPECT_NE(refusal(head + R"("chanel": 1})").find("channel"), std::string::npos)
        << "a typo is named with the key it resembles";
}

// A 220 Hz string with a finger; a press of 1 mm is 0.1 N.
MidiPerformer performer(MidiMapping m = default_midi_mapping()) {
    return MidiPerformer(std::move(m), {"finger", 220.0, 100.0});
}

double finger_in(const MidiPerformer::Round& r) {
    for (const auto& request : r.parameters())
        if (request.what == ParameterRequest::What::FingerPosition) return request.value;
    return -1;
}

TEST(MidiPerformer, ANoteStopsTheStringAtItsPitchAndBowsItUntilReleased) {
    MidiPerformer p = performer();
    p.receive({K::NoteOn, 1, 64, 127});  // E4, a fifth above A3
    const auto r = p.advance(0.01);
    EXPECT_NEAR(finger_in(r), std::pow(2.0, -7.0 / 12), 1e-12);
    EXPECT_TRUE(r.bow_changed);
    EXPECT_NEAR(r.press, 0.2 / 100.0, 1e-15) << "velocity 127: the map's top force";
    EXPECT_EQ(r.slide_speed, 0.1) << "at the map's bow speed";
    const auto later = p.advance(0.01);
    EXPECT_FALSE(later.bow_changed) << "an unchanged bow is not sent again";
    EXPECT_EQ(finger_in(later), -1) << "nor an unchanged finger";
    p.receive({K::NoteOff, 1, 64, 0});
    const auto lifted = p.advance(0.01);
    EXPECT_TRUE(lifted.bow_changed);
    EXPECT_EQ(lifted.press, 0.0);
    EXPECT_EQ(lifted.slide_speed, 0.0) << "the lifted bow stays where it was";
    EXPECT_FALSE(p.advance(0.01).bow_changed);
}

TEST(MidiPerformer, EachStrokeChangesBowAndALegatoNoteKeepsIt) {
    MidiPerformer p = performer();
    p.receive({K::NoteOn, 1, 57, 1});
    EXPECT_GT(p.advance(0.1).slide_speed, 0);
    p.receive({K::NoteOn, 1, 59, 100});  // slurred: same stroke, same force
    const auto slur = p.advance(0.1);
    EXPECT_FALSE(slur.bow_changed);
    EXPECT_NEAR(slur.press, 0.02 / 100.0, 1e-15) << "velocity 1: the map's least force";
    p.receive({K::NoteOff, 1, 59, 0});
    EXPECT_NEAR(finger_in(p.advance(0.01)), 1.0, 1e-12) << "back to the note still held";
    p.receive({K::NoteOff, 1, 57, 0});
    EXPECT_EQ(p.advance(0.01).slide_speed, 0.0);
    p.receive({K::NoteOn, 1, 57, 64});
    EXPECT_LT(p.advance(0.1).slide_speed, 0) << "the next stroke bows the other way";
}

TEST(MidiPerformer, ControllersSetForceSpeedAndVibratoAndTheWheelBends) {
    MidiPerformer p = performer();
    p.receive({K::NoteOn, 1, 69, 100});          // A4, the octave
    p.receive({K::Control, 1, 2, 127});          // bow force 0.5 N
    p.receive({K::ChannelPressure, 1, 0, 127});  // bow speed 0.4 m/s
    const auto r = p.advance(0.01);
    EXPECT_NEAR(r.press, 0.5 / 100.0, 1e-15);
    EXPECT_NEAR(r.slide_speed, 0.4, 1e-15);
    p.receive({K::PitchBend, 1, 0, 8191});
    EXPECT_NEAR(finger_in(p.advance(0.01)), 0.5 * std::pow(2.0, -2.0 * 8191 / 8192 / 12), 1e-12);
    p.receive({K::PitchBend, 1, 0, 0});
    p.receive({K::Control, 1, 1, 127});   // vibrato ±0.5 semitone
    p.receive({K::Control, 1, 11, 127});  // at 8 Hz
    double lowest = 1, highest = 0;
    for (int i = 0; i < 500; ++i) {  // a second in 2 ms rounds
        const double f = finger_in(p.advance(0.002));
        if (f < 0) continue;
        lowest = std::min(lowest, f), highest = std::max(highest, f);
    }
    EXPECT_NEAR(highest, 0.5 * std::pow(2.0, 0.5 / 12), 1e-4);
    EXPECT_NEAR(lowest, 0.5 * std::pow(2.0, -0.5 / 12), 1e-4);
}

TEST(MidiPerformer, OtherChannelsUnreachableNotesAndAMissingFingerAreSaid) {
    MidiMapping m = default_midi_mapping();
    m.channel = 2;
    MidiPerformer p = performer(m);
    p.receive({K::NoteOn, 1, 64, 100});
    EXPECT_FALSE(p.bowing()) << "channel 1 is not heard";
    p.receive({K::NoteOn, 2, 40, 100});  // E2, below the open A3
    const auto r = p.advance(0.01);
    ASSERT_EQ(r.refused().size(), 1u);
    const std::string said = p.describe(r.refused()[0]);
    EXPECT_NE(said.find("note 40"), std::string::npos) << said;
    EXPECT_NE(said.find("220 Hz"), std::string::npos) << said;
    EXPECT_FALSE(p.bowing());
    p.receive({K::NoteOn, 2, 56, 100});  // a semitone below: within reach of the open string?
    EXPECT_FALSE(p.bowing()) << "a whole semitone flat is not the open string";

    MidiMapping pressure = default_midi_mapping();
    pressure.controls.push_back({20, MidiTarget::FingerPressure, {}, 0.0, 1.0});
    MidiPerformer open(pressure, {"", 0.0, 100.0});
    open.receive({K::NoteOn, 1, 30, 100});
    EXPECT_TRUE(open.bowing()) << "without a finger every note bows the open string";
    open.receive({K::Control, 1, 20, 100});
    const auto round = open.advance(0.01);
    ASSERT_EQ(round.refused().size(), 1u);
    EXPECT_NE(open.describe(round.refused()[0]).find("no finger"), std::string::npos);
    EXPECT_TRUE(round.parameters().empty());
}

TEST(MidiPerformer, AParameterRouteSetsTheModelsParameter) {
    MidiMapping m = default_midi_mapping();
    m.controls.push_back({74, MidiTarget::Parameter, {"friction", "mu_s"}, 0.5, 1.0});
    MidiPerformer p = performer(m);
    p.receive({K::Control, 1, 74, 127});
    p.receive({K::Control, 1, 7, 127});  // unmapped: nothing
    p.receive({K::Control, 1, 74, 0});   // the newest value of a round acts
    p.receive({K::Control, 1, 74, 127});
    const auto r = p.advance(0.01);
    ASSERT_EQ(r.parameters().size(), 1u);
    EXPECT_EQ(p.parameter_of(r.parameters()[0]).text(), "friction.mu_s");
    EXPECT_EQ(r.parameters()[0].value, 1.0);
}

// The performer plays inside an LV2 plugin's run(): once built, taking messages and giving
// rounds neither allocates nor frees.
TEST(MidiPerformer, PlaysWithoutAllocatingOnAMarkedRealTimeThread) {
    MidiMapping m = default_midi_mapping();
    m.controls.push_back({74, MidiTarget::Parameter, {"friction", "mu_s"}, 0.5, 1.0});
    MidiPerformer p = performer(m);
    const std::uint64_t before = realtime_allocations() + realtime_deallocations();
    double moved = 0;
    {
        const RealtimeThreadMark mark;
        for (int i = 0; i < 2000; ++i) {
            p.receive({K::NoteOn, 1, 57 + i % 24, 1 + i % 127});
            p.receive({K::Control, 1, 74, i % 128});
            p.receive({K::Control, 1, 1, i % 128});
            p.receive({K::PitchBend, 1, 0, i % 8192});
            p.receive({K::NoteOn, 1, 20, 100});  // refused: out of reach
            if (i % 3 == 0) p.receive({K::NoteOff, 1, 57 + i % 24, 0});
            const auto r = p.advance(0.002);
            moved += r.slide_speed + static_cast<double>(r.parameters().size());
        }
    }
    EXPECT_EQ(realtime_allocations() + realtime_deallocations(), before);
    EXPECT_GT(moved, 0);
}

}  // namespace
}  // namespace archet::midi
