#include "archet/files/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "archet/common/printable_text.hpp"

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

JsonObjectReader::JsonObjectReader(const nlohmann::ordered_json& object, std::string where)
    : object_(object), where_(std::move(where)) {
    if (!object_.is_object())
        throw InputError(where_,
                         std::string("expected a JSON object, found ") + type_name(object_));
}

bool JsonObjectReader::has(const std::string& key) const {
    return object_.contains(key);
}

void JsonObjectReader::ask(const std::string& key) {
    if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.push_back(key);
}

const nlohmann::ordered_json& JsonObjectReader::get(const std::string& key) {
    const nlohmann::ordered_json* v = optional(key);
    if (!v) throw InputError(where_, "missing key " + quoted_text(key));
    return *v;
}

const nlohmann::ordered_json* JsonObjectReader::optional(const std::string& key) {
    ask(key);
    auto it = object_.find(key);
    return it == object_.end() ? nullptr : &*it;
}

double JsonObjectReader::number(const std::string& key) {
    return checked_number(key, get(key));
}

double JsonObjectReader::checked_number(const std::string& key,
                                        const nlohmann::ordered_json& v) const {
    if (!v.is_number())
        throw InputError(where_, quoted_text(key) + " must be a number, found " + type_name(v));
    const double x = v.get<double>();
    if (!std::isfinite(x)) throw InputError(where_, quoted_text(key) + " must be a finite number");
    return x;
}

double JsonObjectReader::number(const std::string& key, double fallback) {
    const nlohmann::ordered_json* v = optional(key);
    return v ? checked_number(key, *v) : fallback;
}

int JsonObjectReader::integer(const std::string& key, int fallback) {
    const nlohmann::ordered_json* found = optional(key);
    if (!found) return fallback;
    const auto& v = *found;
    if (!v.is_number_integer())
        throw InputError(where_, quoted_text(key) + " must be an integer, found " + type_name(v));
    const bool fits = v.is_number_unsigned()
                          ? v.get<std::uint64_t>() <= std::numeric_limits<int>::max()
                          : v.get<std::int64_t>() >= std::numeric_limits<int>::min() &&
                                v.get<std::int64_t>() <= std::numeric_limits<int>::max();
    if (!fits)
        throw InputError(where_, key + " " + v.dump() +
                                     " is out of range: a whole number here lies between "
                                     "-2147483648 and 2147483647");
    return v.get<int>();
}

std::string JsonObjectReader::text(const std::string& key) {
    return checked_text(key, get(key));
}

std::string JsonObjectReader::checked_text(const std::string& key,
                                           const nlohmann::ordered_json& v) const {
    if (!v.is_string())
        throw InputError(where_, quoted_text(key) + " must be a string, found " + type_name(v));
    return v.get<std::string>();
}

std::string JsonObjectReader::text(const std::string& key, const std::string& fallback) {
    const nlohmann::ordered_json* v = optional(key);
    return v ? checked_text(key, *v) : fallback;
}

const nlohmann::ordered_json& JsonObjectReader::array(const std::string& key) {
    const auto& v = get(key);
    if (!v.is_array())
        throw InputError(where_, quoted_text(key) + " must be an array, found " + type_name(v));
    return v;
}

const nlohmann::ordered_json& JsonObjectReader::object(const std::string& key) {
    const auto& v = get(key);
    if (!v.is_object())
        throw InputError(where_, quoted_text(key) + " must be an object, found " + type_name(v));
    return v;
}

void JsonObjectReader::finish() const {
    for (auto it = object_.begin(); it != object_.end(); ++it) {
        if (std::find(known_.begin(), known_.end(), it.key()) != known_.end()) continue;
        std::string message = "unknown key " + quoted_text(it.key());
        const std::string hint =
            closest_word(it.key(), std::set<std::string>(known_.begin(), known_.end()));
        if (!hint.empty()) message += "; did you mean " + quoted_text(hint) + "?";
        throw InputError(where_, message);
    }
}

}  // namespace archet
