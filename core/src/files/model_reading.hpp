#pragma once
// Reads models and gestures from a parsed JSON document, element by element, naming each in
// every error: one reader for a document nlohmann parsed and one simdjson parsed (FastJson),
// which give the same model or the same error. Private to the file sources.

#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "archet/common/input_error.hpp"
#include "archet/common/input_limits.hpp"
#include "archet/common/printable_text.hpp"
#include "archet/files/json_reader.hpp"
#include "archet/files/model_file.hpp"
#include "archet/model/element_kinds.hpp"
#include "archet/model/gesture_validation.hpp"

namespace archet::model_reading {

// `text` as one of `values`, or an error naming `r`'s object and the values it may be.
template <class Enum, class Json>
Enum parse_enum(const std::string& text, std::initializer_list<Enum> values,
                const BasicJsonObjectReader<Json>& r, const char* key) {
    for (Enum v : values)
        if (text == to_string(v)) return v;
    std::set<std::string> names;
    for (Enum v : values) names.insert(to_string(v));
    std::string message =
        "unknown " + std::string(key) + " " + quoted_text(text) + "; expected one of:";
    for (const auto& n : names) message += " " + n;
    const std::string hint = closest_word(text, names);
    if (!hint.empty()) message += " (did you mean " + quoted_text(hint) + "?)";
    throw InputError(r.where(), message);
}

template <class Json>
std::optional<std::pair<double, double>> read_display(BasicJsonObjectReader<Json>& r) {
    const auto d = r.optional("display");
    if (!d) return std::nullopt;
    if (!d->is_array() || d->size() != 2 || !(*d)[0].is_number() || !(*d)[1].is_number())
        throw InputError(r.where(), "\"display\" must be [x, y], two numbers");
    return std::make_pair((*d)[0].template get<double>(), (*d)[1].template get<double>());
}

template <class Json>
void check_header(BasicJsonObjectReader<Json>& r, const std::string& format, int version) {
    const std::string found = r.text("format");
    if (found != format)
        throw InputError(
            r.where(), "\"format\" is " + quoted_text(found) + ", expected " + quoted_text(format));
    const int v = r.integer("version", -1);
    if (v < 1) throw InputError(r.where(), "\"version\" must be a positive integer");
    if (v > version)
        throw InputError(r.where(), "written by a newer Archet (format version " +
                                        std::to_string(v) + "); this build reads up to version " +
                                        std::to_string(version));
}

// A kind's numbers, by the parameter table: those with a file default may be left out.
template <class Json, class Element>
void read_parameters(BasicJsonObjectReader<Json>& r, Element& e) {
    for (const auto& p : kind_parameters(e.kind))
        e.*p.field =
            p.file_default ? r.number(p.info.name, *p.file_default) : r.number(p.info.name);
}

template <class Json>
std::vector<std::string> read_ids(BasicJsonObjectReader<Json>& r, const std::string& key) {
    std::vector<std::string> ids;
    for (const auto& id : r.array(key)) {
        if (!id.is_string())
            throw InputError(r.where(), "\"" + key + "\" must list mass ids (strings)");
        ids.push_back(id.template get<std::string>());
    }
    return ids;
}

template <class Json>
void read_modal_point(BasicJsonObjectReader<Json>& r, Mat& m) {
    m.modes = read_ids(r, "modes");
    const auto& weights = r.array("weights");
    for (const auto& w : weights) {
        if (!w.is_number()) throw InputError(r.where(), "\"weights\" must be numbers");
        m.weights.push_back(w.template get<double>());
    }
}

template <class Json>
Mat read_mat(const Json& item, std::size_t index) {
    BasicJsonObjectReader<Json> r(item, "mass", index);
    Mat m;
    m.id = r.text("id");
    m.kind = parse_enum(
        r.text("type"),
        {MatKind::Mass, MatKind::Fixed, MatKind::Oscillator, MatKind::Gesture, MatKind::ModalPoint},
        r, "mass type");
    m.rate = r.text("rate", "audio");
    read_parameters(r, m);
    if (m.kind == MatKind::Gesture)
        m.axis = parse_enum(r.text("axis"), {GestureAxis::Slide, GestureAxis::Press}, r, "axis");
    if (m.kind == MatKind::ModalPoint) read_modal_point(r, m);
    m.display = read_display(r);
    r.finish();
    return m;
}

template <class Json>
Lia read_lia(const Json& item, std::size_t index) {
    BasicJsonObjectReader<Json> r(item, "link", index);
    Lia l;
    l.id = r.text("id");
    l.kind = parse_enum(r.text("type"),
                        {LiaKind::Spring, LiaKind::Damper, LiaKind::SpringDamper, LiaKind::Buffer,
                         LiaKind::BowFriction, LiaKind::Finger},
                        r, "link type");
    l.rate = r.text("rate", "audio");
    if (l.kind == LiaKind::BowFriction) {  // its bow and string masses are `from` and `to`
        l.from = r.text("bow"), l.to = r.text("string");
        l.press = r.text("press"), l.surface = r.text("surface");
    } else if (l.kind == LiaKind::Finger) {  // the string it stops, from the bridge to the nut
        l.along = read_ids(r, "along");
    } else {
        l.from = r.text("from"), l.to = r.text("to");
    }
    read_parameters(r, l);
    l.display = read_display(r);
    r.finish();
    return l;
}

template <class Json>
Control read_control(const Json& item, std::size_t index) {
    BasicJsonObjectReader<Json> r(item, "control", index);
    Control c;
    c.id = r.text("id");
    c.rate = r.text("rate", "audio");
    c.target = ParameterName::parse(r.text("target"), r.where() + " target");
    const auto& source_object = r.object("source");
    BasicJsonObjectReader<Json> s(source_object, r.where() + " source");
    c.source =
        parse_enum(s.text("type"),
                   {Control::Source::Envelope, Control::Source::Gesture, Control::Source::Position},
                   s, "source type");
    switch (c.source) {
        case Control::Source::Envelope: {
            for (const auto& p : s.array("points")) {
                if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
                    throw InputError(s.where(), "each envelope point must be [time, value]");
                c.envelope.emplace_back(p[0].template get<double>(), p[1].template get<double>());
            }
            break;
        }
        case Control::Source::Gesture:
            c.axis =
                parse_enum(s.text("axis"), {GestureAxis::Slide, GestureAxis::Press}, s, "axis");
            break;
        case Control::Source::Position:
            c.element = s.text("element");
            break;
    }
    c.gain = s.number("gain", 1.0);
    c.offset = s.number("offset", 0.0);
    s.finish();
    const auto& range = r.array("range");
    if (range.size() != 2 || !range[0].is_number() || !range[1].is_number())
        throw InputError(r.where(), "\"range\" must be [minimum, maximum]");
    c.minimum = range[0].template get<double>();
    c.maximum = range[1].template get<double>();
    r.finish();
    return c;
}

template <class Json>
Probe read_probe(const Json& item, std::size_t index) {
    BasicJsonObjectReader<Json> r(item, "probe", index);
    Probe p;
    p.id = r.text("id");
    p.kind = parse_enum(
        r.text("kind"),
        {ProbeKind::Position, ProbeKind::Velocity, ProbeKind::Force, ProbeKind::NormalForce,
         ProbeKind::FrictionForce, ProbeKind::SlipVelocity, ProbeKind::Energy, ProbeKind::PowerIn},
        r, "probe kind");
    if (p.kind != ProbeKind::Energy && p.kind != ProbeKind::PowerIn) p.element = r.text("element");
    r.finish();
    return p;
}

template <class Json>
Output read_output(const Json& item, std::size_t index) {
    BasicJsonObjectReader<Json> r(item, "output #" + std::to_string(index + 1));
    Output o;
    o.element = r.text("element");
    o.signal =
        parse_enum(r.text("signal"),
                   {Output::Signal::Position, Output::Signal::Velocity, Output::Signal::Force}, r,
                   "output signal");
    o.gain = r.number("gain", 1.0);
    r.finish();
    return o;
}

template <class Json>
std::vector<GestureKeyframe> read_keyframes(BasicJsonObjectReader<Json>& r) {
    std::vector<GestureKeyframe> frames;
    std::size_t i = 0;
    for (const auto& item : r.array("keyframes")) {
        BasicJsonObjectReader<Json> k(item, r.where() + " keyframe #" + std::to_string(++i));
        frames.push_back({k.number("t"), k.number("slide"), k.number("press")});
        k.finish();
    }
    return frames;
}

template <class Json>
Model read_model(const Json& root, const std::string& source) {
    BasicJsonObjectReader<Json> r(root, source);
    check_header(r, "archet-model", kModelFormatVersion);
    Model m;
    m.name = r.text("name", "");
    m.description = r.text("description", "");
    m.sample_rate = r.number("sample_rate", 48000.0);
    m.output_gain = r.number("output_gain", 1.0);
    if (const auto rates = r.optional("rates")) {
        if (!rates->is_array()) throw InputError(source, "\"rates\" must be an array");
        m.rates.clear();
        std::size_t i = 0;
        for (const auto& rate : *rates) {
            BasicJsonObjectReader<Json> rr(rate, "rate level", i++);
            m.rates.push_back({rr.text("id"), rr.integer("divider", 1)});
            rr.finish();
        }
    }
    const auto& mats = r.array("masses");
    const auto& lias = r.array("links");
    if (mats.size() + lias.size() > limits::kElements)
        throw InputError(source, "holds " + std::to_string(mats.size()) + " masses and " +
                                     std::to_string(lias.size()) +
                                     " links; a model may have at most " +
                                     std::to_string(limits::kElements) + " elements");
    // Iterated, not indexed: simdjson finds an array's element i by walking to it.
    std::size_t i = 0;
    for (const auto& item : mats) m.mats.push_back(read_mat(item, i++));
    i = 0;
    for (const auto& item : lias) m.lias.push_back(read_lia(item, i++));
    auto read_list = [&](const char* key, auto reader, auto& into) {
        const auto list = r.optional(key);
        if (!list) return;
        if (!list->is_array())
            throw InputError(source, std::string("\"") + key + "\" must be an array");
        std::size_t n = 0;
        for (const auto& item : *list) into.push_back(reader(item, n++));
    };
    read_list("controls", read_control<Json>, m.controls);
    read_list("probes", read_probe<Json>, m.probes);
    read_list("outputs", read_output<Json>, m.outputs);
    if (const auto g = r.optional("gesture")) {
        BasicJsonObjectReader<Json> gr(*g, source + " gesture");
        const std::string name = gr.text("name", "");
        m.gesture = Gesture(name, read_keyframes(gr));
        gr.finish();
    }
    r.finish();
    return m;
}

template <class Json>
Gesture read_gesture(const Json& root, const std::string& source) {
    BasicJsonObjectReader<Json> r(root, source);
    check_header(r, "archet-gesture", kGestureFormatVersion);
    const std::string name = r.text("name", "");
    auto frames = read_keyframes(r);
    r.finish();
    Gesture gesture(name, std::move(frames));
    if (auto problem = check_gesture(gesture, source)) throw *problem;
    return gesture;
}

}  // namespace archet::model_reading
