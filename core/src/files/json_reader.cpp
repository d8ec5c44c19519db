#include "archet/files/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "archet/common/printable_text.hpp"
#include "fast_json.hpp"

namespace archet {

namespace {
std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = above;
        }
    }
    return row[b.size()];
}

const char* type_name(const nlohmann::ordered_json& v) {
    return v.type_name();
}
const char* type_name(const FastJson& v) {
    return v.type_name();
}

// Calls f with each key of an object (a view), in the file's order.
template <class F>
void for_each_key(const nlohmann::ordered_json& object, F&& f) {
    for (auto it = object.begin(); it != object.end(); ++it) f(std::string_view(it.key()));
}
template <class F>
void for_each_key(const FastJson& object, F&& f) {
    object.for_each_key(f);
}
}  // namespace

std::string closest_word(const std::string& word, const std::set<std::string>& candidates) {
    std::string best;
    std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
    for (const auto& c : candidates) {
        const std::size_t d = edit_distance(word, c);
        if (d < best_distance) best_distance = d, best = c;
    }
    return best;
}

template <class Value>
BasicJsonObjectReader<Value>::BasicJsonObjectReader(const Value& object, std::string where)
    : object_(object), where_(std::move(where)) {
    check_is_object();
}

template <class Value>
BasicJsonObjectReader<Value>::BasicJsonObjectReader(const Value& object, const char* kind,
                                                    std::size_t index)
    : object_(object), kind_(kind), index_(index) {
    check_is_object();
}

template <class Value>
void BasicJsonObjectReader<Value>::check_is_object() const {
    if (!object_.is_object())
        throw InputError(where(),
                         std::string("expected a JSON object, found ") + type_name(object_));
}

template <class Value>
const std::string& BasicJsonObjectReader<Value>::where() const {
    if (kind_ && where_.empty()) {
        const std::string kind = kind_;
        const Found id = object_.is_object() ? find("id") : Found{};
        where_ = id && (*id).is_string()
                     ? kind + " " + quoted_text((*id).template get<std::string>())
                     : kind + " #" + std::to_string(index_ + 1);
    }
    return where_;
}

template <class Value>
bool BasicJsonObjectReader<Value>::has(const std::string& key) const {
    return static_cast<bool>(find(key));
}

template <class Value>
auto BasicJsonObjectReader<Value>::find(const std::string& key) const -> Found {
    if constexpr (kViews) {
        return object_.find(key);
    } else {
        auto it = object_.find(key);
        return it == object_.end() ? nullptr : &*it;
    }
}

template <class Value>
void BasicJsonObjectReader<Value>::ask(const std::string& key) {
    const auto asked = known_.begin() + static_cast<std::ptrdiff_t>(asked_);
    if (std::find(known_.begin(), asked, key) != asked) return;
    if (asked_ == kMostKeys) throw std::logic_error("a JSON object read for more keys than kept");
    known_[asked_++] = key;
}

template <class Value>
auto BasicJsonObjectReader<Value>::get(const std::string& key) -> Ref {
    Found v = optional(key);
    if (!v) throw InputError(where(), "missing key " + quoted_text(key));
    return *v;
}

template <class Value>
auto BasicJsonObjectReader<Value>::optional(const std::string& key) -> Found {
    ask(key);
    return find(key);
}

template <class Value>
double BasicJsonObjectReader<Value>::number(const std::string& key) {
    return checked_number(key, get(key));
}

template <class Value>
double BasicJsonObjectReader<Value>::checked_number(const std::string& key, const Value& v) const {
    if (!v.is_number())
        throw InputError(where(), quoted_text(key) + " must be a number, found " + type_name(v));
    const double x = v.template get<double>();
    if (!std::isfinite(x)) throw InputError(where(), quoted_text(key) + " must be a finite number");
    return x;
}

template <class Value>
double BasicJsonObjectReader<Value>::number(const std::string& key, double fallback) {
    const Found v = optional(key);
    return v ? checked_number(key, *v) : fallback;
}

template <class Value>
int BasicJsonObjectReader<Value>::integer(const std::string& key, int fallback) {
    const Found found = optional(key);
    if (!found) return fallback;
    const auto& v = *found;
    if (!v.is_number_integer())
        throw InputError(where(), quoted_text(key) + " must be an integer, found " + type_name(v));
    const bool fits = v.is_number_unsigned()
                          ? v.template get<std::uint64_t>() <= std::numeric_limits<int>::max()
                          : v.template get<std::int64_t>() >= std::numeric_limits<int>::min() &&
                                v.template get<std::int64_t>() <= std::numeric_limits<int>::max();
    if (!fits)
        throw InputError(where(), key + " " + v.dump() +
                                      " is out of range: a whole number here lies between "
                                      "-2147483648 and 2147483647");
    return v.template get<int>();
}

template <class Value>
std::string BasicJsonObjectReader<Value>::text(const std::string& key) {
    return checked_text(key, get(key));
}

template <class Value>
std::string BasicJsonObjectReader<Value>::checked_text(const std::string& key,
                                                       const Value& v) const {
    if (!v.is_string())
        throw InputError(where(), quoted_text(key) + " must be a string, found " + type_name(v));
    return v.template get<std::string>();
}

template <class Value>
std::string BasicJsonObjectReader<Value>::text(const std::string& key,
                                               const std::string& fallback) {
    const Found v = optional(key);
    return v ? checked_text(key, *v) : fallback;
}

template <class Value>
auto BasicJsonObjectReader<Value>::array(const std::string& key) -> Ref {
    Ref v = get(key);
    if (!v.is_array())
        throw InputError(where(), quoted_text(key) + " must be an array, found " + type_name(v));
    return v;
}

template <class Value>
auto BasicJsonObjectReader<Value>::object(const std::string& key) -> Ref {
    Ref v = get(key);
    if (!v.is_object())
        throw InputError(where(), quoted_text(key) + " must be an object, found " + type_name(v));
    return v;
}

template <class Value>
void BasicJsonObjectReader<Value>::finish() const {
    const auto asked = known_.begin() + static_cast<std::ptrdiff_t>(asked_);
    for_each_key(object_, [&](std::string_view key) {
        if (std::find(known_.begin(), asked, key) != asked) return;
        std::string message = "unknown key " + quoted_text(std::string(key));
        const std::string hint =
            closest_word(std::string(key), std::set<std::string>(known_.begin(), asked));
        if (!hint.empty()) message += "; did you mean " + quoted_text(hint) + "?";
        throw InputError(where(), message);
    });
}

template class BasicJsonObjectReader<nlohmann::ordered_json>;
template class BasicJsonObjectReader<FastJson>;

}  // namespace archet
