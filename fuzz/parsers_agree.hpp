#pragma once
// Whether simdjson and nlohmann read a file alike, for the model and gesture fuzzers: where
// simdjson parses the text (parses_fast()), `read` (parse, then write out again) must give the
// same text or the same error as with a byte-order mark in front, which sends it to nlohmann.

#include <string>

#include "archet/common/input_error.hpp"
#include "archet/files/model_file.hpp"

template <class Read>
bool parsers_agree(const std::string& text, Read read) {
    if (!archet::parses_fast(text)) return true;
    auto outcome = [&](const std::string& t) -> std::string {
        try {
            return read(t);
        } catch (const archet::InputError& e) {
            return e.what();
        }
    };
    return outcome(text) == outcome("\xEF\xBB\xBF" + text);
}
