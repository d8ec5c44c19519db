#include "archet/files/model_file.hpp"

#include <unistd.h>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "archet/common/input_limits.hpp"
#include "archet/common/number_text.hpp"
#include "archet/common/printable_text.hpp"
#include "archet/files/json_reader.hpp"
#include "archet/files/output_target.hpp"
#include "archet/model/element_kinds.hpp"
#include "archet/model/gesture_validation.hpp"

namespace archet {

using Json = nlohmann::ordered_json;

namespace {

template <class Enum>
Enum parse_enum(const std::string& text, std::initializer_list<Enum> values,
                const std::string& where, const std::string& key) {
    std::set<std::string> names;
    for (Enum v : values) {
        if (text == to_string(v)) return v;
        names.insert(to_string(v));
    }
    std::string message = "unknown " + key + " " + quoted_text(text) + "; expected one of:";
    for (const auto& n : names) message += " " + n;
    const std::string hint = closest_word(text, names);
    if (!hint.empty()) message += " (did you mean " + quoted_text(hint) + "?)";
    throw InputError(where, message);
}

std::string element_where(const std::string& kind, const Json& item, std::size_t index) {
    if (item.is_object() && item.contains("id") && item["id"].is_string())
        return kind + " " + quoted_text(item["id"].get<std::string>());
    return kind + " #" + std::to_string(index + 1);
}

std::optional<std::pair<double, double>> read_display(JsonObjectReader& r) {
    const Json* d = r.optional("display");
    if (!d) return std::nullopt;
    if (!d->is_array() || d->size() != 2 || !(*d)[0].is_number() || !(*d)[1].is_number())
        throw InputError(r.where(), "\"display\" must be [x, y], two numbers");
    return std::make_pair((*d)[0].get<double>(), (*d)[1].get<double>());
}

void check_header(JsonObjectReader& r, const std::string& format, int version) {
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
template <class Element>
void read_parameters(JsonObjectReader& r, Element& e) {
    for (const auto& p : kind_parameters(e.kind))
        e.*p.field =
            p.file_default ? r.number(p.info.name, *p.file_default) : r.number(p.info.name);
}

std::vector<std::string> read_ids(JsonObjectReader& r, const std::string& key) {
    std::vector<std::string> ids;
    for (const auto& id : r.array(key)) {
        if (!id.is_string())
            throw InputError(r.where(), "\"" + key + "\" must list mass ids (strings)");
        ids.push_back(id.get<std::string>());
    }
    return ids;
}

void read_modal_point(JsonObjectReader& r, Mat& m) {
    m.modes = read_ids(r, "modes");
    const Json& weights = r.array("weights");
    for (const auto& w : weights) {
        if (!w.is_number()) throw InputError(r.where(), "\"weights\" must be numbers");
        m.weights.push_back(w.get<double>());
    }
}

Mat read_mat(const Json& item, std::size_t index) {
    JsonObjectReader r(item, element_where("mass", item, index));
    Mat m;
    m.id = r.text("id");
    m.kind = parse_enum(
        r.text("type"),
        {MatKind::Mass, MatKind::Fixed, MatKind::Oscillator, MatKind::Gesture, MatKind::ModalPoint},
        r.where(), "mass type");
    m.rate = r.text("rate", "audio");
    read_parameters(r, m);
    if (m.kind == MatKind::Gesture)
        m.axis =
            parse_enum(r.text("axis"), {GestureAxis::Slide, GestureAxis::Press}, r.where(), "axis");
    if (m.kind == MatKind::ModalPoint) read_modal_point(r, m);
    m.display = read_display(r);
    r.finish();
    return m;
}

Lia read_lia(const Json& item, std::size_t index) {
    JsonObjectReader r(item, element_where("link", item, index));
    Lia l;
    l.id = r.text("id");
    l.kind = parse_enum(r.text("type"),
                        {LiaKind::Spring, LiaKind::Damper, LiaKind::SpringDamper, LiaKind::Buffer,
                         LiaKind::BowFriction, LiaKind::Finger},
                        r.where(), "link type");
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

Control read_control(const Json& item, std::size_t index) {
    JsonObjectReader r(item, element_where("control", item, index));
    Control c;
    c.id = r.text("id");
    c.rate = r.text("rate", "audio");
    c.target = ParameterName::parse(r.text("target"), r.where() + " target");
    JsonObjectReader s(r.object("source"), r.where() + " source");
    c.source =
        parse_enum(s.text("type"),
                   {Control::Source::Envelope, Control::Source::Gesture, Control::Source::Position},
                   s.where(), "source type");
    switch (c.source) {
        case Control::Source::Envelope: {
            for (const auto& p : s.array("points")) {
                if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
                    throw InputError(s.where(), "each envelope point must be [time, value]");
                c.envelope.emplace_back(p[0].get<double>(), p[1].get<double>());
            }
            break;
        }
        case Control::Source::Gesture:
            c.axis = parse_enum(s.text("axis"), {GestureAxis::Slide, GestureAxis::Press}, s.where(),
                                "axis");
            break;
        case Control::Source::Position:
            c.element = s.text("element");
            break;
    }
    c.gain = s.number("gain", 1.0);
    c.offset = s.number("offset", 0.0);
    s.finish();
    const Json& range = r.array("range");
    if (range.size() != 2 || !range[0].is_number() || !range[1].is_number())
        throw InputError(r.where(), "\"range\" must be [minimum, maximum]");
    c.minimum = range[0].get<double>();
    c.maximum = range[1].get<double>();
    r.finish();
    return c;
}

Probe read_probe(const Json& item, std::size_t index) {
    JsonObjectReader r(item, element_where("probe", item, index));
    Probe p;
    p.id = r.text("id");
    p.kind = parse_enum(
        r.text("kind"),
        {ProbeKind::Position, ProbeKind::Velocity, ProbeKind::Force, ProbeKind::NormalForce,
         ProbeKind::FrictionForce, ProbeKind::SlipVelocity, ProbeKind::Energy, ProbeKind::PowerIn},
        r.where(), "probe kind");
    if (p.kind != ProbeKind::Energy && p.kind != ProbeKind::PowerIn) p.element = r.text("element");
    r.finish();
    return p;
}

Output read_output(const Json& item, std::size_t index) {
    JsonObjectReader r(item, "output #" + std::to_string(index + 1));
    Output o;
    o.element = r.text("element");
    o.signal =
        parse_enum(r.text("signal"),
                   {Output::Signal::Position, Output::Signal::Velocity, Output::Signal::Force},
                   r.where(), "output signal");
    o.gain = r.number("gain", 1.0);
    r.finish();
    return o;
}

std::vector<GestureKeyframe> read_keyframes(JsonObjectReader& r) {
    std::vector<GestureKeyframe> frames;
    const Json& list = r.array("keyframes");
    for (std::size_t i = 0; i < list.size(); ++i) {
        JsonObjectReader k(list[i], r.where() + " keyframe #" + std::to_string(i + 1));
        frames.push_back({k.number("t"), k.number("slide"), k.number("press")});
        k.finish();
    }
    return frames;
}

Json write_display(const std::optional<std::pair<double, double>>& d) {
    return Json::array({d->first, d->second});
}

Json write_keyframes(const Gesture& g) {
    Json frames = Json::array();
    for (const auto& k : g.keyframes())
        frames.push_back(Json{{"t", k.time}, {"slide", k.slide}, {"press", k.press}});
    return frames;
}

template <class Item, class Writer>
Json write_list(const std::vector<Item>& items, Writer write) {
    Json list = Json::array();
    for (const auto& item : items) list.push_back(write(item));
    return list;
}

Json write_rate(const RateLevel& rl) {
    return Json{{"id", rl.id}, {"divider", rl.divider}};
}

template <class Element>
Json element_header(const Element& e) {
    return Json{{"id", e.id}, {"type", to_string(e.kind)}, {"rate", e.rate}};
}

// A kind's numbers from row `first` to before row `end` of the parameter table.
template <class Element>
void write_parameters(Json& j, const Element& e, std::size_t first, std::size_t end) {
    const auto& rows = kind_parameters(e.kind);
    for (std::size_t i = first; i < std::min(end, rows.size()); ++i)
        j[rows[i].info.name] = e.*rows[i].field;
}

constexpr auto kAllRows = std::numeric_limits<std::size_t>::max();

Json write_mat(const Mat& e) {
    Json j = element_header(e);
    // The file has a gesture point's axis after its position (the first row), before the rest.
    write_parameters(j, e, 0, 1);
    if (e.kind == MatKind::Gesture) j["axis"] = to_string(e.axis);
    if (e.kind == MatKind::ModalPoint) j["modes"] = e.modes, j["weights"] = e.weights;
    write_parameters(j, e, 1, kAllRows);
    if (e.display) j["display"] = write_display(e.display);
    return j;
}

Json write_lia(const Lia& e) {
    Json j = element_header(e);
    if (e.kind == LiaKind::BowFriction) {
        j["bow"] = e.bow(), j["string"] = e.bowed_string(), j["press"] = e.press;
        j["surface"] = e.surface;
    } else if (e.kind == LiaKind::Finger) {
        j["along"] = e.along;
    } else {
        j["from"] = e.from, j["to"] = e.to;
    }
    write_parameters(j, e, 0, kAllRows);
    if (e.display) j["display"] = write_display(e.display);
    return j;
}

Json write_control(const Control& c) {
    Json source{{"type", to_string(c.source)}};
    if (c.source == Control::Source::Envelope) {
        Json points = Json::array();
        for (const auto& [t, v] : c.envelope) points.push_back(Json::array({t, v}));
        source["points"] = points;
    } else if (c.source == Control::Source::Gesture) {
        source["axis"] = to_string(c.axis);
    } else {
        source["element"] = c.element;
    }
    source["gain"] = c.gain, source["offset"] = c.offset;
    return Json{{"id", c.id},
                {"rate", c.rate},
                {"target", c.target.text()},
                {"source", source},
                {"range", Json::array({c.minimum, c.maximum})}};
}

Json write_probe(const Probe& p) {
    Json j{{"id", p.id}, {"kind", to_string(p.kind)}};
    if (!p.element.empty()) j["element"] = p.element;
    return j;
}

Json write_output(const Output& o) {
    return Json{{"element", o.element}, {"signal", to_string(o.signal)}, {"gain", o.gain}};
}

Json parse_json(const std::string& text, const std::string& source) {
    try {
        return Json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        // Parse errors and numbers beyond double range (1e999) alike.
        throw InputError(source, std::string("malformed JSON: ") + e.what());
    }
}

}  // namespace

Model parse_model(const std::string& text, const std::string& source) {
    const Json root = parse_json(text, source);
    JsonObjectReader r(root, source);
    check_header(r, "archet-model", kModelFormatVersion);
    Model m;
    m.name = r.text("name", "");
    m.description = r.text("description", "");
    m.sample_rate = r.number("sample_rate", 48000.0);
    m.output_gain = r.number("output_gain", 1.0);
    if (const Json* rates = r.optional("rates")) {
        if (!rates->is_array()) throw InputError(source, "\"rates\" must be an array");
        m.rates.clear();
        for (std::size_t i = 0; i < rates->size(); ++i) {
            JsonObjectReader rr((*rates)[i], element_where("rate level", (*rates)[i], i));
            m.rates.push_back({rr.text("id"), rr.integer("divider", 1)});
            rr.finish();
        }
    }
    const Json& mats = r.array("masses");
    const Json& lias_list = r.array("links");
    if (mats.size() + lias_list.size() > limits::kElements)
        throw InputError(source, "holds " + std::to_string(mats.size()) + " masses and " +
                                     std::to_string(lias_list.size()) +
                                     " links; a model may have at most " +
                                     std::to_string(limits::kElements) + " elements");
    for (std::size_t i = 0; i < mats.size(); ++i) m.mats.push_back(read_mat(mats[i], i));
    const Json& lias = r.array("links");
    for (std::size_t i = 0; i < lias.size(); ++i) m.lias.push_back(read_lia(lias[i], i));
    auto read_list = [&](const char* key, auto reader, auto& into) {
        const Json* list = r.optional(key);
        if (!list) return;
        if (!list->is_array())
            throw InputError(source, std::string("\"") + key + "\" must be an array");
        for (std::size_t i = 0; i < list->size(); ++i) into.push_back(reader((*list)[i], i));
    };
    read_list("controls", read_control, m.controls);
    read_list("probes", read_probe, m.probes);
    read_list("outputs", read_output, m.outputs);
    if (const Json* g = r.optional("gesture")) {
        JsonObjectReader gr(*g, source + " gesture");
        const std::string name = gr.text("name", "");
        m.gesture = Gesture(name, read_keyframes(gr));
        gr.finish();
    }
    r.finish();
    return m;
}

std::string format_model(const Model& m) {
    Json root;
    root["format"] = "archet-model";
    root["version"] = kModelFormatVersion;
    root["name"] = m.name;
    root["description"] = m.description;
    root["sample_rate"] = m.sample_rate;
    root["output_gain"] = m.output_gain;
    root["rates"] = write_list(m.rates, write_rate);
    root["masses"] = write_list(m.mats, write_mat);
    root["links"] = write_list(m.lias, write_lia);
    root["controls"] = write_list(m.controls, write_control);
    root["probes"] = write_list(m.probes, write_probe);
    root["outputs"] = write_list(m.outputs, write_output);
    if (m.gesture)
        root["gesture"] =
            Json{{"name", m.gesture->name()}, {"keyframes", write_keyframes(*m.gesture)}};
    return root.dump(2) + "\n";
}

Gesture parse_gesture(const std::string& text, const std::string& source) {
    const Json root = parse_json(text, source);
    JsonObjectReader r(root, source);
    check_header(r, "archet-gesture", kGestureFormatVersion);
    const std::string name = r.text("name", "");
    auto frames = read_keyframes(r);
    r.finish();
    Gesture gesture(name, std::move(frames));
    if (auto problem = check_gesture(gesture, source)) throw *problem;
    return gesture;
}

std::string format_gesture(const Gesture& g) {
    Json root{{"format", "archet-gesture"},
              {"version", kGestureFormatVersion},
              {"name", g.name()},
              {"keyframes", write_keyframes(g)}};
    return root.dump(2) + "\n";
}

std::string read_text_file(const std::filesystem::path& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError(path.string(), "is a folder; give the file inside it");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string(), "cannot open the file for reading");
    // Read at most one byte past the limit: /dev/zero, a FIFO or a huge file stop there.
    std::string text;
    char chunk[1 << 16];
    while (text.size() <= limits::kFileBytes && in.read(chunk, sizeof chunk).gcount() > 0)
        text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (in.bad()) throw InputError(path.string(), "read error");
    if (text.size() > limits::kFileBytes)
        throw InputError(path.string(),
                         "is larger than " + std::to_string(limits::kFileBytes >> 20) +
                             " MiB, the most a model, gesture or take file may hold; "
                             "is it the right file?");
    return text;
}

Model load_model_file(const std::filesystem::path& path) {
    return parse_model(read_text_file(path), path.string());
}

Gesture load_gesture_file(const std::filesystem::path& path) {
    return parse_gesture(read_text_file(path), path.string());
}

void write_file_atomically(const std::filesystem::path& path, const std::string& contents) {
    const OutputTarget target = output_target(path);
    const std::filesystem::path temp = target.in_place ? target.path : target.temporary();
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) throw InputError(path.string(), "cannot write here (is the folder writable?)");
        out << contents;
        out.flush();
        if (!out) {
            out.close();
            std::error_code ignored;
            if (!target.in_place) std::filesystem::remove(temp, ignored);
            throw InputError(path.string(), target.in_place
                                                ? "write failed"
                                                : "write failed (disk full?); the existing file "
                                                  "is untouched");
        }
    }
    if (target.in_place) return;
    std::error_code ec;
    std::filesystem::rename(temp, target.path, ec);
    if (ec) {
        std::filesystem::remove(temp, ec);
        throw InputError(path.string(), "cannot replace the file: " + ec.message());
    }
}

}  // namespace archet
