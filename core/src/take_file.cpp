#include "archet/take_file.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "archet/input_error.hpp"
#include "archet/json_reader.hpp"
#include "archet/model_file.hpp"

namespace archet {

namespace {

using Json = nlohmann::ordered_json;

Json parse(const std::filesystem::path& path) {
    try {
        return Json::parse(read_text_file(path));
    } catch (const Json::exception& e) {
        throw InputError(path.string(), std::string("is not valid JSON: ") + e.what());
    }
}

void expect_format(JsonObjectReader& r, const std::string& format) {
    if (r.text("format") != format)
        throw InputError(r.where(), "\"format\" must be \"" + format + "\"");
    if (r.integer("version", 0) != 1)
        throw InputError(r.where(), "\"version\" must be 1 (written by this Archet)");
}

std::uint64_t count(JsonObjectReader& r, const std::string& key) {
    const double v = r.number(key);
    if (!(v >= 0) || v > 9.0e15 || std::floor(v) != v)
        throw InputError(r.where() + "." + key, "must be a whole number of samples");
    return static_cast<std::uint64_t>(v);
}

}  // namespace

std::string format_take(const TakeDescription& t) {
    Json j;
    j["format"] = "archet-take";
    j["version"] = 1;
    j["sample_rate"] = t.sample_rate;
    j["frames"] = t.frames;
    j["start_tick"] = t.start_tick;
    j["state"] = t.has_state;
    j["parameters"] = t.has_parameters;
    return j.dump(2) + "\n";
}

TakeDescription read_take_file(const std::filesystem::path& path) {
    const Json j = parse(path);
    if (!j.is_object()) throw InputError(path.string(), "must hold a JSON object");
    JsonObjectReader r(j, path.string());
    expect_format(r, "archet-take");
    TakeDescription t;
    t.sample_rate = r.number("sample_rate");
    if (!(t.sample_rate >= 1000 && t.sample_rate <= 1e6))
        throw InputError(path.string() + ".sample_rate", "must be 1000 to 1000000 Hz");
    t.frames = count(r, "frames");
    t.start_tick = count(r, "start_tick");
    const Json* state = r.optional("state");
    const Json* parameters = r.optional("parameters");
    if (!state || !state->is_boolean() || !parameters || !parameters->is_boolean())
        throw InputError(path.string(), "\"state\" and \"parameters\" must be true or false");
    t.has_state = state->get<bool>(), t.has_parameters = parameters->get<bool>();
    r.finish();
    return t;
}

std::string format_parameter_changes(const std::vector<ParameterChange>& changes) {
    Json j;
    j["format"] = "archet-take-parameters";
    j["version"] = 1;
    j["changes"] = Json::array();
    for (const auto& c : changes)
        j["changes"].push_back({{"tick", c.tick},
                                {"parameter", c.parameter},
                                {"value", c.value},
                                {"glide_samples", c.glide_samples}});
    return j.dump(2) + "\n";
}

std::vector<ParameterChange> read_parameter_changes(const std::filesystem::path& path) {
    const Json j = parse(path);
    if (!j.is_object()) throw InputError(path.string(), "must hold a JSON object");
    JsonObjectReader r(j, path.string());
    expect_format(r, "archet-take-parameters");
    std::vector<ParameterChange> changes;
    const Json& list = r.array("changes");
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string where = path.string() + ": change " + std::to_string(i);
        if (!list[i].is_object()) throw InputError(where, "must be an object");
        JsonObjectReader c(list[i], where);
        ParameterChange change;
        change.tick = count(c, "tick");
        change.parameter = c.text("parameter");
        change.value = c.number("value");
        change.glide_samples = c.integer("glide_samples", 1);
        if (change.glide_samples < 1) throw InputError(where, "glide_samples must be at least 1");
        if (!changes.empty() && change.tick < changes.back().tick)
            throw InputError(where, "changes must be in the order they were made");
        c.finish();
        changes.push_back(change);
    }
    r.finish();
    return changes;
}

}  // namespace archet
