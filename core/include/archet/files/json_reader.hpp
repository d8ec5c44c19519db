#pragma once
// Reads one JSON object field by field, naming the element and key in every error, and
// refuses keys it does not know (with the closest known one as a hint) so that a typo in a
// model file is an error rather than a silently ignored parameter.

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "archet/common/input_error.hpp"

namespace archet {

/// Reads one object of a document that nlohmann::ordered_json or simdjson (FastJson, for model
/// and gesture files) parsed. Values it finds come back as references into an nlohmann document
/// and as views (held by value) into a simdjson one.
template <class Value>
class BasicJsonObjectReader {
    static constexpr bool kViews = !std::is_same_v<Value, nlohmann::ordered_json>;

  public:
    using Ref = std::conditional_t<kViews, Value, const Value&>;
    using Found = std::conditional_t<kViews, std::optional<Value>, const Value*>;

    BasicJsonObjectReader(const Value& object, std::string where);
    /// Element `index` (from 0) of a list of `kind`s, named in errors by its id when it has
    /// one as a string (mass "s1"), else by its place (mass #3): the name is spelt only for an
    /// error, which a large model's thousands of elements then do not pay for. `kind` is a
    /// literal.
    BasicJsonObjectReader(const Value& object, const char* kind, std::size_t index);
    /// It keeps a reference to the object: never one to a temporary.
    BasicJsonObjectReader(Value&& object, std::string where) = delete;
    BasicJsonObjectReader(Value&& object, const char* kind, std::size_t index) = delete;

    bool has(const std::string& key) const;
    double number(const std::string& key);
    double number(const std::string& key, double fallback);
    int integer(const std::string& key, int fallback);
    std::string text(const std::string& key);
    std::string text(const std::string& key, const std::string& fallback);
    Ref array(const std::string& key);
    Ref object(const std::string& key);
    Found optional(const std::string& key);

    /// Throws if the object holds a key none of the calls above asked for.
    void finish() const;
    /// The object's name in errors.
    const std::string& where() const;

  private:
    Ref get(const std::string& key);
    Found find(const std::string& key) const;
    /// Notes a key as one this object may hold (for finish()).
    void ask(const std::string& key);
    double checked_number(const std::string& key, const Value& v) const;
    std::string checked_text(const std::string& key, const Value& v) const;

    void check_is_object() const;

    const Value& object_;
    mutable std::string where_;  ///< spelt when first asked for, for an element of a list
    const char* kind_ = nullptr;
    std::size_t index_ = 0;
    /// The keys asked for: a handful, searched in order, in a fixed array (a key of up to 15
    /// characters is kept without allocating).
    static constexpr std::size_t kMostKeys = 32;
    std::array<std::string, kMostKeys> known_;
    std::size_t asked_ = 0;
};

using JsonObjectReader = BasicJsonObjectReader<nlohmann::ordered_json>;

/// The closest of `candidates` to `word` by edit distance, or "" when none is close.
std::string closest_word(const std::string& word, const std::set<std::string>& candidates);

}  // namespace archet
