#include "archet/files/take_file.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "archet/common/input_error.hpp"
#include "archet/common/printable_text.hpp"
#include "archet/files/json_reader.hpp"
#include "archet/files/model_file.hpp"

namespace archet {

namespace {

using Json = nlohmann::ordered_json;

Json parse(const std::string& text, const std::string& source) {
    try {
        return Json::parse(text);
    } catch (const Json::exception& e) {
        throw InputError(source, std::string("is not valid JSON: ") + e.what());
    }
}

bool flag(JsonObjectReader& r, const std::string& key, bool fallback) {
    const Json* value = r.optional(key);
    if (!value) return fallback;
    if (!value->is_boolean()) throw InputError(r.where() + "." + key, "must be true or false");
    return value->get<bool>();
}

void expect_format(JsonObjectReader& r, const std::string& format) {
    if (r.text("format") != format)
        throw InputError(r.where(), "\"format\" must be \"" + format + "\"");
    if (r.integer("version", 0) != 1)
        throw InputError(r.where(), "\"version\" must be 1 (written by this Archet)");
}

std::uint64_t count(JsonObjectReader& r, const std::string& key,
                    const std::string& of = "samples") {
    const double v = r.number(key);
    if (!(v >= 0) || v > 9.0e15 || std::floor(v) != v)
        throw InputError(r.where() + "." + key, "must be a whole number of " + of);
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
    j["complete"] = t.complete;
    j["interrupted"] = t.interrupted;
    if (t.interrupted) j["interrupted_by"] = t.interrupted_by;
    j["clipped_samples"] = t.clipped_samples;
    j["peak"] = t.peak;
    if (t.dropped_samples > 0) j["dropped_samples"] = t.dropped_samples;
    if (t.dropped_events > 0) j["dropped_events"] = t.dropped_events;
    j["scheme"] = t.scheme;
    return j.dump(2) + "\n";
}

TakeDescription parse_take(const std::string& text, const std::string& source) {
    const Json j = parse(text, source);
    if (!j.is_object()) throw InputError(source, "must hold a JSON object");
    JsonObjectReader r(j, source);
    expect_format(r, "archet-take");
    TakeDescription t;
    t.sample_rate = r.number("sample_rate");
    if (!(t.sample_rate >= 1000 && t.sample_rate <= 1e6))
        throw InputError(source + ".sample_rate", "must be 1000 to 1000000 Hz");
    t.frames = count(r, "frames");
    t.start_tick = count(r, "start_tick");
    const Json* state = r.optional("state");
    const Json* parameters = r.optional("parameters");
    if (!state || !state->is_boolean() || !parameters || !parameters->is_boolean())
        throw InputError(source, "\"state\" and \"parameters\" must be true or false");
    t.has_state = state->get<bool>(), t.has_parameters = parameters->get<bool>();
    t.complete = flag(r, "complete", true);
    t.interrupted = flag(r, "interrupted", false);
    t.interrupted_by = r.text("interrupted_by", t.interrupted ? "unknown" : "");
    if (!t.interrupted && !t.interrupted_by.empty())
        throw InputError(source + ".interrupted_by", "is given but \"interrupted\" is false");
    if (!is_printable_text(t.interrupted_by))
        throw InputError(source + ".interrupted_by", "may hold only printable characters");
    if (t.interrupted && t.interrupted_by.empty())
        throw InputError(source + ".interrupted_by", "must say why the take was interrupted");
    t.clipped_samples = r.has("clipped_samples") ? count(r, "clipped_samples") : 0;
    t.peak = r.number("peak", 0.0);
    if (!(t.peak >= 0) || !std::isfinite(t.peak))
        throw InputError(source + ".peak", "must be a finite level of 0 or more");
    if (t.clipped_samples > t.frames && t.complete)
        throw InputError(source + ".clipped_samples", "counts more samples than the take holds");
    t.dropped_samples = r.has("dropped_samples") ? count(r, "dropped_samples") : 0;
    t.dropped_events = r.has("dropped_events") ? count(r, "dropped_events", "events") : 0;
    t.scheme = r.integer("scheme", 1);
    if (t.scheme < 1 || t.scheme > kSchemeRevision)
        throw InputError(source + ".scheme", "must be 1 to " + std::to_string(kSchemeRevision) +
                                                 " (a take played by this Archet or an older one)");
    r.finish();
    return t;
}

TakeDescription read_take_file(const std::filesystem::path& path) {
    return parse_take(read_text_file(path), path.string());
}

void check_in_flight(const ParameterChange& c, const std::string& where) {
    if (c.done < 0 || c.done >= c.glide_samples)
        throw InputError(where, "done must be 0 to glide_samples - 1 (a glide under way)");
}

std::string format_parameter_changes(const std::vector<ParameterChange>& changes) {
    Json j;
    j["format"] = "archet-take-parameters";
    j["version"] = 1;
    j["changes"] = Json::array();
    for (const auto& c : changes) {
        Json change{{"tick", c.tick},
                    {"parameter", c.parameter},
                    {"value", c.value},
                    {"glide_samples", c.glide_samples}};
        if (c.from) change["from"] = *c.from, change["done"] = c.done;
        j["changes"].push_back(std::move(change));
    }
    return j.dump(2) + "\n";
}

std::vector<ParameterChange> parse_parameter_changes(const std::string& text,
                                                     const std::string& source) {
    const Json j = parse(text, source);
    if (!j.is_object()) throw InputError(source, "must hold a JSON object");
    JsonObjectReader r(j, source);
    expect_format(r, "archet-take-parameters");
    std::vector<ParameterChange> changes;
    const Json& list = r.array("changes");
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string where = source + ": change " + std::to_string(i);
        if (!list[i].is_object()) throw InputError(where, "must be an object");
        JsonObjectReader c(list[i], where);
        ParameterChange change;
        change.tick = count(c, "tick");
        change.parameter = c.text("parameter");
        change.value = c.number("value");
        change.glide_samples = c.integer("glide_samples", 1);
        if (change.glide_samples < 1) throw InputError(where, "glide_samples must be at least 1");
        if (c.has("from")) {
            change.from = c.number("from");
            change.done = c.integer("done", 0);
            check_in_flight(change, where);
        }
        if (!changes.empty() && change.tick < changes.back().tick)
            throw InputError(where, "changes must be in the order they were made");
        c.finish();
        changes.push_back(change);
    }
    r.finish();
    return changes;
}

std::vector<ParameterChange> read_parameter_changes(const std::filesystem::path& path) {
    return parse_parameter_changes(read_text_file(path), path.string());
}

}  // namespace archet
