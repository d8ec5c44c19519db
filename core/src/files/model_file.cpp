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
#include "archet/files/output_target.hpp"
#include "archet/model/element_kinds.hpp"
#include "archet/model/gesture_validation.hpp"
#include "fast_json.hpp"
#include "model_reading.hpp"

namespace archet {

using Json = nlohmann::ordered_json;

namespace {

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

// Reads a file's document with `read`: parsed by simdjson where parse_fast_json() takes it,
// else by nlohmann, which words the errors of what simdjson refuses.
template <class Read>
auto read_document(const std::string& text, const std::string& source, Read&& read) {
    {
        FastJsonDocument fast;  // freed before nlohmann parses
        if (parse_fast_json(text, fast)) return read(fast.root);
    }
    return read(parse_json(text, source));
}

}  // namespace

bool parses_fast(const std::string& text) {
    FastJsonDocument fast;
    return parse_fast_json(text, fast);
}

namespace {}  // namespace

Model parse_model(const std::string& text, const std::string& source) {
    return read_document(text, source,
                         [&](const auto& root) { return model_reading::read_model(root, source); });
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
    return read_document(
        text, source, [&](const auto& root) { return model_reading::read_gesture(root, source); });
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
