#include "fast_json.hpp"

#include <algorithm>
#include <vector>

namespace archet {

namespace {

bool is_container(simdjson::dom::element e) {
    return e.type() == simdjson::dom::element_type::ARRAY ||
           e.type() == simdjson::dom::element_type::OBJECT;
}

// Whether any object under `value` holds a key twice: an element's handful of keys, compared
// pairwise (as nlohmann's ordered map finds them). The walk keeps its own stack of the arrays
// and objects still to look into, so nesting costs no recursion and numbers no memory.
bool has_repeated_key(simdjson::dom::element value) {
    std::vector<simdjson::dom::element> pending;
    if (is_container(value)) pending.push_back(value);
    std::vector<std::string_view> keys;
    while (!pending.empty()) {
        const simdjson::dom::element e = pending.back();
        pending.pop_back();
        if (e.type() == simdjson::dom::element_type::ARRAY) {
            for (simdjson::dom::element item : simdjson::dom::array(e))
                if (is_container(item)) pending.push_back(item);
            continue;
        }
        keys.clear();
        for (simdjson::dom::key_value_pair m : simdjson::dom::object(e)) {
            if (std::find(keys.begin(), keys.end(), m.key) != keys.end()) return true;
            keys.push_back(m.key);
            if (is_container(m.value)) pending.push_back(m.value);
        }
    }
    return false;
}

}  // namespace

const char* FastJson::type_name() const {
    switch (type()) {
        case Type::OBJECT:
            return "object";
        case Type::ARRAY:
            return "array";
        case Type::STRING:
            return "string";
        case Type::BOOL:
            return "boolean";
        case Type::NULL_VALUE:
            return "null";
        default:
            return "number";
    }
}

std::size_t FastJson::size() const {
    if (is_array()) {
        // simdjson's count stops at 0xFFFFFF: past it, count them.
        const simdjson::dom::array array(element_);
        std::size_t count = array.size();
        if (count < 0xFFFFFF) return count;
        count = 0;
        for ([[maybe_unused]] simdjson::dom::element item : array) ++count;
        return count;
    }
    if (is_object()) return simdjson::dom::object(element_).size();
    return type() == Type::NULL_VALUE ? 0 : 1;
}

std::optional<FastJson> FastJson::find(std::string_view key) const {
    if (!is_object()) return std::nullopt;
    simdjson::dom::element found;
    if (simdjson::dom::object(element_).at_key(key).get(found) != simdjson::SUCCESS)
        return std::nullopt;
    return FastJson(found);
}

FastJson::Iterator FastJson::begin() const {
    return Iterator(simdjson::dom::array(element_).begin());
}

FastJson::Iterator FastJson::end() const {
    return Iterator(simdjson::dom::array(element_).end());
}

bool parse_fast_json(const std::string& text, FastJsonDocument& document) {
    if (text.starts_with("\xEF\xBB\xBF")) return false;
    simdjson::dom::element root;
    if (document.parser.parse(text).get(root) != simdjson::SUCCESS) return false;
    if (has_repeated_key(root)) return false;
    document.root = FastJson(root);
    return true;
}

}  // namespace archet
