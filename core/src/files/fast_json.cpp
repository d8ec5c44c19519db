#include "fast_json.hpp"

#include <algorithm>
#include <vector>

namespace archet {

namespace {

// Whether any object under `value` holds a key twice: a handful of keys an object, compared
// pairwise; the walk keeps its own stack, so nesting costs no recursion.
bool has_repeated_key(simdjson::dom::element value) {
    std::vector<simdjson::dom::element> pending{value};
    std::vector<std::string_view> keys;
    while (!pending.empty()) {
        const simdjson::dom::element e = pending.back();
        pending.pop_back();
        if (e.type() == simdjson::dom::element_type::ARRAY) {
            for (simdjson::dom::element item : simdjson::dom::array(e)) pending.push_back(item);
        } else if (e.type() == simdjson::dom::element_type::OBJECT) {
            keys.clear();
            for (simdjson::dom::key_value_pair m : simdjson::dom::object(e)) {
                if (std::find(keys.begin(), keys.end(), m.key) != keys.end()) return true;
                keys.push_back(m.key);
                pending.push_back(m.value);
            }
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
    if (is_array()) return simdjson::dom::array(element_).size();
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
