#include "archet/midi/midi_mapping.hpp"

#include <cmath>
#include <set>
#include <utility>

#include "archet/common/input_error.hpp"
#include "archet/common/number_text.hpp"
#include "archet/files/json_reader.hpp"
#include "archet/files/model_file.hpp"

namespace archet::midi {

namespace {

using Json = nlohmann::ordered_json;

constexpr const char* kFormat = "archet-midi-map";

struct TargetInfo {
    MidiTarget target;
    const char* name;
    const char* unit;
    double lowest, highest;  ///< what a route's range may span
};

// Bounds wide enough for any string we build and narrow enough that a slip of a digit is
// caught: 5 N is ten times a violinist's hardest stroke, 2 m/s twice the fastest.
constexpr TargetInfo kTargets[] = {
    {MidiTarget::BowForce, "bow_force", "N", 0, 5},
    {MidiTarget::BowSpeed, "bow_speed", "m/s", 0, 2},
    {MidiTarget::VibratoDepth, "vibrato_depth", "semitones", 0, 2},
    {MidiTarget::VibratoRate, "vibrato_rate", "Hz", 0, 20},
    {MidiTarget::FingerPressure, "finger_pressure", "", 0, 1},
    {MidiTarget::BowPosition, "bow_position", "", 0.02, 0.45},
    {MidiTarget::Parameter, "parameter", "", -1e300, 1e300},
};

const TargetInfo& info(MidiTarget t) {
    for (const auto& i : kTargets)
        if (i.target == t) return i;
    return kTargets[0];
}

MidiTarget target_named(const std::string& name, const std::string& where) {
    std::set<std::string> names;
    for (const auto& i : kTargets) {
        if (name == i.name) return i.target;
        names.insert(i.name);
    }
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InputError(where, "unknown target \"" + name + "\"; one of " + list);
}

// [MIN, MAX], finite, each within `lowest` … `highest`.
std::pair<double, double> read_range(const Json& value, const std::string& where, double lowest,
                                     double highest, const char* unit) {
    if (!value.is_array() || value.size() != 2 || !value[0].is_number() || !value[1].is_number())
        throw InputError(where, "expected [MIN, MAX], two numbers");
    const double a = value[0].get<double>(), b = value[1].get<double>();
    for (double v : {a, b})
        if (!std::isfinite(v) || v < lowest || v > highest)
            throw InputError(where, format_number(v) + " is out of range: give " +
                                        format_number(lowest) + " to " + format_number(highest) +
                                        (*unit ? std::string(" ") + unit : std::string()));
    return {a, b};
}

ControlRoute read_route(const Json& entry, const std::string& where) {
    JsonObjectReader r(entry, where);
    ControlRoute route;
    const double controller = r.number("controller");
    if (controller != std::floor(controller) || controller < 0 || controller > kChannelPressure)
        throw InputError(where + ".controller",
                         "give a controller number 0 to 127, or 128 for channel pressure");
    route.controller = static_cast<int>(controller);
    route.target = target_named(r.text("target"), where + ".target");
    if (route.target == MidiTarget::Parameter)
        route.parameter = ParameterName::parse(r.text("parameter"), where + ".parameter");
    const TargetInfo& t = info(route.target);
    std::tie(route.minimum, route.maximum) =
        read_range(r.array("range"), where + ".range", t.lowest, t.highest, t.unit);
    r.finish();
    return route;
}

Json range_json(double a, double b) {
    return Json::array({a, b});
}

}  // namespace

const ControlRoute* MidiMapping::route(int controller) const {
    for (const auto& c : controls)
        if (c.controller == controller) return &c;
    return nullptr;
}

MidiMapping default_midi_mapping() {
    MidiMapping m;
    m.controls = {{2, MidiTarget::BowForce, {}, 0.0, 0.5},
                  {4, MidiTarget::BowPosition, {}, 0.05, 0.3},
                  {1, MidiTarget::VibratoDepth, {}, 0.0, 0.5},
                  {11, MidiTarget::VibratoRate, {}, 3.0, 8.0},
                  {kChannelPressure, MidiTarget::BowSpeed, {}, 0.0, 0.4}};
    return m;
}

std::string to_string(MidiTarget target) {
    return info(target).name;
}

MidiMapping parse_midi_mapping(const std::string& text, const std::string& source) {
    Json root;
    try {
        root = Json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw InputError(source, std::string("malformed JSON: ") + e.what());
    }
    JsonObjectReader r(root, source);
    if (r.text("format") != kFormat)
        throw InputError(source + ".format", std::string("expected \"") + kFormat + "\"");
    if (r.integer("version", 1) != 1)
        throw InputError(source + ".version", "this Archet reads version 1");
    MidiMapping m;
    const double channel = r.number("channel", 0);
    if (channel != std::floor(channel) || channel < 0 || channel > 16)
        throw InputError(source + ".channel", "give 1 to 16, or 0 for every channel");
    m.channel = static_cast<int>(channel);
    m.bend_range = r.number("bend_range", m.bend_range);
    if (!std::isfinite(m.bend_range) || m.bend_range < 0 || m.bend_range > 24)
        throw InputError(source + ".bend_range", "give 0 to 24 semitones");
    if (const Json* v = r.optional("velocity_force"))
        std::tie(m.velocity_force_min, m.velocity_force_max) =
            read_range(*v, source + ".velocity_force", 0, 5, "N");
    m.bow_speed = r.number("bow_speed", m.bow_speed);
    if (!std::isfinite(m.bow_speed) || m.bow_speed <= 0 || m.bow_speed > 2)
        throw InputError(source + ".bow_speed", "give a speed above 0 and at most 2 m/s");
    if (const Json* controls = r.optional("controls")) {
        if (!controls->is_array()) throw InputError(source + ".controls", "expected an array");
        if (controls->size() > kChannelPressure + 1)
            throw InputError(source + ".controls", "at most one entry per controller (129)");
        std::set<int> seen;
        for (std::size_t i = 0; i < controls->size(); ++i) {
            const std::string where = source + ".controls[" + std::to_string(i) + "]";
            ControlRoute route = read_route((*controls)[i], where);
            if (!seen.insert(route.controller).second)
                throw InputError(where + ".controller", "controller " +
                                                            std::to_string(route.controller) +
                                                            " is mapped twice; keep one entry");
            m.controls.push_back(std::move(route));
        }
    }
    r.finish();
    return m;
}

MidiMapping load_midi_mapping(const std::filesystem::path& path) {
    return parse_midi_mapping(read_text_file(path), path.string());
}

std::string write_midi_mapping(const MidiMapping& m) {
    Json controls = Json::array();
    for (const auto& c : m.controls) {
        Json entry{{"controller", c.controller}, {"target", to_string(c.target)}};
        if (c.target == MidiTarget::Parameter) entry["parameter"] = c.parameter.text();
        entry["range"] = range_json(c.minimum, c.maximum);
        controls.push_back(std::move(entry));
    }
    const Json root{{"format", kFormat},
                    {"version", 1},
                    {"channel", m.channel},
                    {"bend_range", m.bend_range},
                    {"velocity_force", range_json(m.velocity_force_min, m.velocity_force_max)},
                    {"bow_speed", m.bow_speed},
                    {"controls", std::move(controls)}};
    return root.dump(2) + "\n";
}

}  // namespace archet::midi
