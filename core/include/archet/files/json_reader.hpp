#pragma once
// Reads one JSON object field by field, naming the element and key in every error, and
// refuses keys it does not know (with the closest known one as a hint) so that a typo in a
// model file is an error rather than a silently ignored parameter.

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "archet/common/input_error.hpp"

namespace archet {

class JsonObjectReader {
  public:
    JsonObjectReader(const nlohmann::ordered_json& object, std::string where);

    bool has(const std::string& key) const;
    double number(const std::string& key);
    double number(const std::string& key, double fallback);
    int integer(const std::string& key, int fallback);
    std::string text(const std::string& key);
    std::string text(const std::string& key, const std::string& fallback);
    const nlohmann::ordered_json& array(const std::string& key);
    const nlohmann::ordered_json& object(const std::string& key);
    const nlohmann::ordered_json* optional(const std::string& key);

    /// Throws if the object holds a key none of the calls above asked for.
    void finish() const;
    const std::string& where() const { return where_; }

  private:
    const nlohmann::ordered_json& get(const std::string& key);
    /// Notes a key as one this object may hold (for finish()).
    void ask(const std::string& key);
    double checked_number(const std::string& key, const nlohmann::ordered_json& v) const;
    std::string checked_text(const std::string& key, const nlohmann::ordered_json& v) const;

    const nlohmann::ordered_json& object_;
    std::string where_;
    std::vector<std::string> known_;  ///< the keys asked for: a handful, searched in order
};

/// The closest of `candidates` to `word` by edit distance, or "" when none is close.
std::string closest_word(const std::string& word, const std::set<std::string>& candidates);

}  // namespace archet
