#pragma once
// A read-only view of a JSON value that simdjson parsed, with the part of nlohmann::json's
// interface the model and gesture readers use, so that one reader reads either: simdjson
// parses a model twenty times faster than nlohmann's DOM (a large model's swap was mostly
// parsing). parse_fast_json() takes only the documents both libraries read alike. Private to
// the file sources.

#include <simdjson.h>

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

namespace archet {

class FastJson {
  public:
    FastJson() = default;
    explicit FastJson(simdjson::dom::element element) : element_(element) {}

    bool is_object() const { return type() == Type::OBJECT; }
    bool is_array() const { return type() == Type::ARRAY; }
    bool is_string() const { return type() == Type::STRING; }
    bool is_number() const { return is_number_integer() || type() == Type::DOUBLE; }
    bool is_number_integer() const { return type() == Type::INT64 || type() == Type::UINT64; }
    /// nlohmann keeps every integer written without a minus sign as unsigned.
    bool is_number_unsigned() const {
        return type() == Type::UINT64 || (type() == Type::INT64 && int64() >= 0);
    }
    const char* type_name() const;

    /// Elements of an array, members of an object (what nlohmann's size() counts).
    std::size_t size() const;
    /// Array element i. Walks the array from its start: iterate rather than index long arrays.
    template <class Index>
    requires std::is_integral_v<Index> FastJson operator[](Index i) const {
        return FastJson(element_.at(static_cast<std::size_t>(i)).value());
    }
    /// Object member `key`; the caller checked it is there (contains()).
    FastJson operator[](const char* key) const {
        const std::optional<FastJson> member = find(key);
        assert(member);
        return *member;
    }
    bool contains(const char* key) const { return find(key).has_value(); }
    std::optional<FastJson> find(std::string_view key) const;

    template <class T>
    T get() const {
        if constexpr (std::is_same_v<T, std::string>)
            return std::string(std::string_view(element_));
        else if constexpr (std::is_same_v<T, double>)
            return double(element_);
        else if constexpr (std::is_same_v<T, std::uint64_t>)
            return std::uint64_t(element_);
        else {
            static_assert(std::is_same_v<T, int> || std::is_same_v<T, std::int64_t>);
            return static_cast<T>(int64());  // after the caller's range check, as nlohmann
        }
    }
    /// The value as JSON text (error messages).
    std::string dump() const { return simdjson::minify(element_); }

    class Iterator;  ///< over an array's elements
    Iterator begin() const;
    Iterator end() const;
    /// Calls f with each key of an object (a view into the document), in the file's order.
    template <class F>
    void for_each_key(F&& f) const {
        for (simdjson::dom::key_value_pair m : simdjson::dom::object(element_)) f(m.key);
    }

  private:
    using Type = simdjson::dom::element_type;
    Type type() const { return element_.type(); }
    std::int64_t int64() const {
        return type() == Type::UINT64 ? static_cast<std::int64_t>(std::uint64_t(element_))
                                      : std::int64_t(element_);
    }
    simdjson::dom::element element_;
};

class FastJson::Iterator {
  public:
    explicit Iterator(simdjson::dom::array::iterator at) : at_(at) {}
    FastJson operator*() const { return FastJson(*at_); }
    Iterator& operator++() {
        ++at_;
        return *this;
    }
    bool operator!=(const Iterator& o) const { return at_ != o.at_; }

  private:
    simdjson::dom::array::iterator at_;
};

/// A parsed document and the parser whose memory its values live in (so it stays put).
struct FastJsonDocument {
    FastJsonDocument() = default;
    FastJsonDocument(const FastJsonDocument&) = delete;
    FastJsonDocument& operator=(const FastJsonDocument&) = delete;

    simdjson::dom::parser parser;
    FastJson root;
};

/// Parses `text` into `document`, or returns false where nlohmann must read it instead: a
/// syntax error (nlohmann words the message), a number beyond double range, an integer beyond
/// 64 bits (nlohmann reads it as a double), nesting deeper than 1,024, a byte-order mark (which
/// nlohmann skips) or an object with a key twice (nlohmann keeps the last, simdjson the first).
bool parse_fast_json(const std::string& text, FastJsonDocument& document);

}  // namespace archet
