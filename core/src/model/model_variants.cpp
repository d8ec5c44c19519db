#include "archet/model/model_variants.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "archet/common/input_error.hpp"
#include "archet/common/input_limits.hpp"
#include "archet/model/bow_contact.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/model/string_points.hpp"

namespace archet {

namespace {

std::set<std::string> bow_parts(const Model& model) {
    std::set<std::string> parts;
    for (const auto& l : model.lias)
        if (l.kind == LiaKind::BowFriction) parts.insert({l.from, l.press, l.surface});
    return parts;
}

// The bow's drawing follows it along the string: its own masses (and its contact point, when it
// has a width) and the hand's points that hold them move by `shift` across the editor.
void shift_bow_drawing(Model& model, const Lia& bow, double shift) {
    std::set<std::string> moved{bow.bow(), bow.press, bow.surface};
    if (bowed_centre(model, bow) != bow.bowed_string()) moved.insert(bow.bowed_string());
    for (const Lia& l : model.lias) {
        const Mat* from = model.find_mat(l.from);
        const Mat* to = model.find_mat(l.to);
        if (from && from->kind == MatKind::Gesture && moved.count(l.to)) moved.insert(l.from);
        if (to && to->kind == MatKind::Gesture && moved.count(l.from)) moved.insert(l.to);
    }
    for (Mat& m : model.mats)
        if (m.display && moved.count(m.id)) m.display->first += shift;
}

// How far across the editor the string mass `to` is drawn from `from` (0 when either is not).
double drawn_apart(const Model& model, const std::string& from, const std::string& to) {
    const Mat* a = model.find_mat(from);
    const Mat* b = model.find_mat(to);
    return a && b && a->display && b->display ? b->display->first - a->display->first : 0.0;
}

}  // namespace

// The chain's masses s1…sN, in order, as the bowed-string builder names them (a string in
// modal form has points there, not masses: none).
std::vector<std::string> string_masses(const Model& model) {
    std::vector<std::string> stations = bow_stations(model);
    if (!stations.empty() && model.find_mat(stations.front())->kind == MatKind::ModalPoint)
        return {};
    return stations;
}

std::vector<std::string> string_links(const Model& model) {
    const std::set<std::string> bow = bow_parts(model);
    std::vector<std::string> links;
    for (const auto& l : model.lias) {
        if (l.kind == LiaKind::BowFriction || l.kind == LiaKind::Buffer) continue;
        const Mat* a = model.find_mat(l.from);
        const Mat* b = model.find_mat(l.to);
        auto string_side = [&](const Mat* m) {
            return m && !bow.count(m->id) &&
                   (m->kind == MatKind::Mass || m->kind == MatKind::Oscillator);
        };
        if (string_side(a) && string_side(b)) links.push_back(l.id);
    }
    return links;
}

void set_variant_parameter(Model& model, const std::string& name, double value) {
    if (name == "string.damping") {
        if (!(std::isfinite(value) && value >= 0))
            throw InputError(name, "must be a damping of 0 N·s/m or more");
        const auto links = string_links(model);
        if (links.empty())
            throw InputError(name,
                             "this model's string has no links (a modal string?); vary "
                             "ELEMENT.damping of its modes instead");
        for (const auto& id : links) model.find_lia(id)->damping = value;
        return;
    }
    if (name == "bow.position") {
        if (!(value > 0 && value < 0.5)) throw InputError(name, "β must be in (0, 0.5)");
        const auto stations = bow_stations(model);
        Lia* bow = first_bow(model);
        if (!bow || stations.size() < 3)
            throw InputError(name,
                             "needs a bowed string of masses s1…sN, or of points there in modal "
                             "form (a built bowed string)");
        const int n = static_cast<int>(stations.size());
        const int index = std::clamp(static_cast<int>(std::lround(value * (n + 1))), 1, n);
        Mat* contact = model.find_mat(bow->bowed_string());
        const std::string was_centred = bowed_centre(model, *bow);
        const bool modal = model.find_mat(stations.front())->kind == MatKind::ModalPoint;
        const bool on_station =
            std::find(stations.begin(), stations.end(), bow->bowed_string()) != stations.end();
        if (modal && !on_station && was_centred == bow->bowed_string())
            throw InputError(name, "the bow's contact \"" + bow->bowed_string() +
                                       "\" is not the mix of three of the string's points "
                                       "that the builder makes; build the string again to move "
                                       "its bow");
        if (contact && was_centred != bow->bowed_string() && modal) {
            // A bow with a width on a string in modal form: its contact mixes the points
            // around the new centre (bow_contact.hpp).
            const int centre = std::clamp(index, 2, n - 1);
            const Mat& before = *model.find_mat(stations[centre - 2]);
            const Mat& at = *model.find_mat(stations[centre - 1]);
            const Mat& after = *model.find_mat(stations[centre]);
            for (const Mat* p : {&before, &at, &after})
                if (!mixes_into(*p, *contact))
                    throw InputError(name, "the string's point \"" + p->id +
                                               "\" reads other modes than the bow's contact "
                                               "\"" +
                                               contact->id + "\"; give it the same modes");
            contact->weights = contact_weights(before, at, after);
        } else if (contact && was_centred != bow->bowed_string()) {
            // A bow with a width: its contact point reads the masses around the new centre.
            const int half = static_cast<int>(contact->modes.size()) / 2;
            const int centre = std::clamp(index, 1 + half, n - half);
            for (int k = 0; k < static_cast<int>(contact->modes.size()); ++k)
                contact->modes[k] = stations[centre - half + k - 1];
        } else {
            const std::string old = bow->bowed_string(), bowed = stations[index - 1];
            bow->to = bowed;  // the bowed string mass (see Lia::bowed_string)
            for (auto& p : model.probes)
                if (p.element == old) p.element = bowed;
        }
        shift_bow_drawing(model, *bow, drawn_apart(model, was_centred, bowed_centre(model, *bow)));
        return;
    }
    set_parameter(model, ParameterName::parse(name), value);
}

std::pair<std::string, std::vector<double>> parse_variation(const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0)
        throw InputError("--vary", "\"" + text + "\": expected PARAM=V1,V2[,...]");
    std::vector<double> values;
    std::stringstream list(text.substr(eq + 1));
    std::string item;
    while (std::getline(list, item, ',')) {
        if (values.size() == limits::kCompareValues)
            throw InputError("--vary", "give at most " + std::to_string(limits::kCompareValues) +
                                           " values to compare");
        std::size_t used = 0;
        double v = 0;
        try {
            v = std::stod(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != item.size() || !std::isfinite(v))
            throw InputError("--vary", "\"" + item + "\" is not a number");
        values.push_back(v);
    }
    if (values.size() < 2) throw InputError("--vary", "give at least two values to compare");
    return {text.substr(0, eq), values};
}

}  // namespace archet
