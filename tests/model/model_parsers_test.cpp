// Model and gesture files are parsed by simdjson and, where it refuses a document or would read
// it otherwise, by nlohmann (fast_json.hpp). A byte-order mark sends a document to nlohmann
// (simdjson refuses it, nlohmann skips it), so each document here is read both ways and must
// give the same model, gesture or error.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "archet/builders/bowed_chain.hpp"
#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"
#include "test_support.hpp"

namespace archet {
namespace {

const std::string kByteOrderMark = "\xEF\xBB\xBF";

// What reading `text` gives: the model written out again, or the error.
template <class Parse, class Format>
std::string outcome(const std::string& text, Parse parse, Format format) {
    try {
        return format(parse(text, "file"));
    } catch (const InputError& e) {
        return std::string("error: ") + e.what();
    }
}

std::string model_outcome(const std::string& text) {
    return outcome(
        text, [](const std::string& t, const std::string& s) { return parse_model(t, s); },
        format_model);
}

std::string gesture_outcome(const std::string& text) {
    return outcome(
        text, [](const std::string& t, const std::string& s) { return parse_gesture(t, s); },
        format_gesture);
}

// simdjson reads `text` (and nlohmann, behind the mark), and the two give the same.
void expect_parsers_agree(const std::string& text) {
    EXPECT_TRUE(parses_fast(text)) << text;
    EXPECT_FALSE(parses_fast(kByteOrderMark + text));
    EXPECT_EQ(model_outcome(text), model_outcome(kByteOrderMark + text)) << text;
}

// What each file of the two folders (models, then gestures) reads as, parsed by simdjson and by
// nlohmann; the files simdjson leaves to nlohmann (malformed JSON) are left out.
struct Readings {
    std::vector<std::string> files, fast, nlohmann;
};
Readings read_both_ways(const std::filesystem::path& models,
                        const std::filesystem::path& gestures) {
    Readings r;
    for (const auto& folder : {models, gestures})
        for (const auto& entry : std::filesystem::directory_iterator(folder)) {
            const std::string text = test::read_file(entry.path());
            const auto read = folder == models ? model_outcome : gesture_outcome;
            if (!parses_fast(text)) continue;
            r.files.push_back(entry.path().string());
            r.fast.push_back(read(text));
            r.nlohmann.push_back(read(kByteOrderMark + text));
        }
    return r;
}

TEST(ModelParsers, ReadEveryShippedModelAndGestureAlike) {
    const Readings r = read_both_ways(test::resource("models"), test::resource("gestures"));
    EXPECT_EQ(r.files.size(), 20u) << "16 models and 4 gestures, each read by simdjson";
    for (std::size_t i = 0; i < r.files.size(); ++i) {
        EXPECT_EQ(r.fast[i].rfind("error", 0), std::string::npos)
            << r.files[i] << ": " << r.fast[i];
        EXPECT_EQ(r.fast[i], r.nlohmann[i]) << r.files[i];
    }
}

TEST(ModelParsers, RefuseEveryBadModelAndGestureAlike) {
    const Readings r =
        read_both_ways(test::test_data("bad-models"), test::test_data("bad-gestures"));
    EXPECT_GE(r.files.size(), 30u);
    for (std::size_t i = 0; i < r.files.size(); ++i)
        EXPECT_EQ(r.fast[i], r.nlohmann[i]) << r.files[i];
}

TEST(ModelParsers, ReadALongChainAlike) {
    const std::string text = format_model(build_bowed_chain(500));
    EXPECT_TRUE(parses_fast(text));
    EXPECT_EQ(model_outcome(text), text);
    EXPECT_EQ(model_outcome(kByteOrderMark + text), text);
}

// A small valid model to break one field at a time.
std::string model_with(const std::string& mass_fields, const std::string& root_fields = "") {
    return R"({"format": "archet-model", "version": 1, )" + root_fields +
           R"("masses": [{"id": "m", "type": "mass", "mass": 0.001)" + mass_fields +
           R"(}, {"id": "g", "type": "fixed"}],
              "links": [{"id": "l", "type": "spring_damper", "from": "m", "to": "g",
                         "stiffness": 10, "damping": 0.001}]})";
}

TEST(ModelParsers, GiveTheSameErrorsAndNumbers) {
    ASSERT_EQ(model_outcome(model_with("")).rfind("error", 0), std::string::npos)
        << model_outcome(model_with(""));
    const std::vector<std::string> documents = {
        model_with(""),
        model_with(R"(, "positon": 0.5)"),                    // an unknown key, with its hint
        model_with(R"(, "position": "0.5")"),                 // a string for a number
        model_with(R"(, "position": null)"),                  // null
        model_with(R"(, "position": true)"),                  // a boolean
        model_with(R"(, "position": [1])"),                   // an array
        model_with(R"(, "position": {"a": 1})"),              // an object
        model_with(R"(, "position": -0)"),                    // an integer zero: +0
        model_with(R"(, "position": -0.0)"),                  // a negative zero
        model_with(R"(, "position": 1e-400)"),                // below the smallest double: 0
        model_with(R"(, "position": 4.9e-324)"),              // the smallest double
        model_with(R"(, "position": 18446744073709551615)"),  // the largest unsigned integer
        model_with(R"(, "display": [1, 2, 3])"),              // a display that is no point
        model_with(R"(, "display": [1.5, -2])"),
        model_with("", R"("rates": [{"id": "audio", "divider": 3000000000}], )"),  // beyond int
        model_with("", R"("rates": [{"id": "audio", "divider": -3000000000}], )"),
        model_with("", R"("rates": [{"id": "audio", "divider": 1.5}], )"),  // not an integer
        model_with("", R"("rates": {"id": "audio"}, )"),                    // not an array
        model_with("", R"("rates": [7], )"),                                // not an object
        model_with("", R"("rates": [{"id": 5}], )"),                        // a number for a string
        model_with("", R"("name": "ünïcode \"quoted\" \u00e9\ud83c\udfbb", )"),
        model_with("", R"("outputs": [{"element": "m", "signal": "loudness"}], )"),
        model_with("", R"("probes": [{"id": "p", "kind": "force"}], )"),  // no element
        model_with(R"(, "pos\u0069tion": 0.5)"),    // a key spelt with an escape
        model_with("", R"("name": "a\u0000b", )"),  // a NUL inside a string
        model_with("", R"("n\u0000ame": "x", )"),   // and inside a key
        R"({"format": "archet-model", "version": 2, "masses": [], "links": []})",
        R"({"format": "archet-model", "version": 1, "masses": [], "links": {}})",
        R"([{"format": "archet-model"}])",
    };
    for (const std::string& text : documents) expect_parsers_agree(text);
}

TEST(ModelParsers, ReadTheLastOfAKeyGivenTwice) {
    const std::string twice = model_with("", R"("name": "first", "name": "second", )");
    EXPECT_FALSE(parses_fast(twice)) << "simdjson would read the first";
    EXPECT_EQ(parse_model(twice).name, "second");
    // Deep inside, and spelt once with an escape: still the last.
    const std::string nested = model_with(R"(, "position": 0.25, "posit\u0069on": 0.5)");
    EXPECT_FALSE(parses_fast(nested));
    EXPECT_EQ(parse_model(nested).mats[0].position, 0.5);
    EXPECT_EQ(model_outcome(model_with("", R"("format": "archet-gesture", )")),
              "error: file: \"format\" is \"archet-gesture\", expected \"archet-model\"");
}

TEST(ModelParsers, LeaveMalformedJsonToNlohmannsWords) {
    const std::vector<std::string> documents = {
        "{\"format\": ", "{} {}", model_with(R"(, "position": 1e400)"), "\"\\ud800\""};
    for (const std::string& text : documents) {
        EXPECT_FALSE(parses_fast(text)) << text;
        EXPECT_NE(model_outcome(text).find("malformed JSON"), std::string::npos) << text;
    }
}

}  // namespace
}  // namespace archet
