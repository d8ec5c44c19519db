#include "archet/model/string_points.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "archet/model/bow_contact.hpp"

namespace archet {

namespace {
// A contact point reads string masses (linked MATs); a modal string's point reads modes,
// which no link touches.
bool is_contact_point(const Model& model, const Mat& m) {
    if (m.kind != MatKind::ModalPoint || m.modes.empty()) return false;
    for (const auto& id : m.modes) {
        bool linked = false;
        for (const auto& l : model.lias) linked = linked || l.from == id || l.to == id;
        if (!linked) return false;
    }
    return true;
}

// The point a contact of a string in modal form is centred on: the one whose weights and its
// neighbours' mix to the contact's, bit for bit as the builder mixes them; or null.
const Mat* modal_contact_centre(const Model& model, const Mat& contact,
                                const std::vector<std::string>& stations) {
    std::vector<const Mat*> points;
    for (const auto& id : stations) points.push_back(model.find_mat(id));
    auto mixes_to_contact = [&](const Mat& before, const Mat& at, const Mat& after) {
        if (!mixes_into(before, contact) || !mixes_into(at, contact) || !mixes_into(after, contact))
            return false;
        for (std::size_t k = 0; k < contact.weights.size(); ++k)
            if (contact_weight(before.weights[k], at.weights[k], after.weights[k]) !=
                contact.weights[k])
                return false;
        return true;
    };
    for (std::size_t i = 1; i + 1 < points.size(); ++i)
        if (mixes_to_contact(*points[i - 1], *points[i], *points[i + 1])) return points[i];
    return nullptr;
}

}  // namespace

std::vector<std::string> bow_stations(const Model& model) {
    std::vector<std::string> stations;
    const Mat* first = model.find_mat("s1");
    const bool modal = first && first->kind == MatKind::ModalPoint;
    for (int i = 1;; ++i) {
        const Mat* m = model.find_mat("s" + std::to_string(i));
        const bool inertial = m && (m->kind == MatKind::Mass || m->kind == MatKind::Oscillator);
        if (!m || (modal ? m->kind != MatKind::ModalPoint : !inertial)) break;
        stations.push_back(m->id);
    }
    return stations;
}

std::string bowed_centre(const Model& model, const Lia& bow) {
    const Mat* end = model.find_mat(bow.bowed_string());
    if (!end) return bow.bowed_string();
    if (is_contact_point(model, *end)) {
        std::size_t best = 0;
        for (std::size_t k = 0; k < end->modes.size() && k < end->weights.size(); ++k)
            if (end->weights[k] > end->weights[best]) best = k;
        return end->modes[best];
    }
    if (end->kind != MatKind::ModalPoint) return end->id;
    const std::vector<std::string> stations = bow_stations(model);
    if (std::find(stations.begin(), stations.end(), end->id) != stations.end()) return end->id;
    const Mat* centre = modal_contact_centre(model, *end, stations);
    return centre ? centre->id : end->id;
}

std::vector<std::size_t> drawn_points(std::size_t points, std::size_t most) {
    std::vector<std::size_t> drawn;
    if (points <= most || most < 2) {
        for (std::size_t i = 0; i < std::min(points, most); ++i) drawn.push_back(i);
        return drawn;
    }
    // i·(points − 1)/(most − 1) rounded to the nearest: steps of at least 1, both ends kept.
    for (std::size_t i = 0; i < most; ++i)
        drawn.push_back((i * (points - 1) + (most - 1) / 2) / (most - 1));
    return drawn;
}

std::vector<std::string> string_points(const Model& model) {
    std::set<std::string> bow_parts, bowed, contacts;
    for (const auto& l : model.lias)
        if (l.kind == LiaKind::BowFriction) {
            bow_parts.insert({l.bow(), l.press, l.surface});
            const std::string centre = bowed_centre(model, l);
            bowed.insert(centre);
            if (centre != l.bowed_string()) contacts.insert(l.bowed_string());
        }
    std::set<std::string> reached;
    if (bowed.empty()) {
        for (const auto& m : model.mats)
            if (m.kind != MatKind::Gesture) reached.insert(m.id);
    } else {
        std::multimap<std::string, std::string> neighbours;
        for (const auto& l : model.lias) {
            if (l.kind == LiaKind::BowFriction || l.kind == LiaKind::Finger) continue;
            neighbours.emplace(l.from, l.to);
            neighbours.emplace(l.to, l.from);
        }
        // A bowed modal point is a string in modal form: its points share its modes and no
        // link, and are the string too (not the points of other bodies the string touches,
        // such as a second bridge on the body's modes).
        reached = bowed;
        std::set<std::string> bowed_modes;
        for (const auto& id : bowed)
            if (const Mat* m = model.find_mat(id); m && m->kind == MatKind::ModalPoint)
                bowed_modes.insert(m->modes.begin(), m->modes.end());
        for (const auto& m : model.mats)
            if (m.kind == MatKind::ModalPoint && !contacts.count(m.id) &&
                std::any_of(m.modes.begin(), m.modes.end(),
                            [&](const std::string& mode) { return bowed_modes.count(mode); }))
                reached.insert(m.id);
        std::vector<std::string> frontier(reached.begin(), reached.end());
        while (!frontier.empty()) {
            const std::string at = frontier.back();
            frontier.pop_back();
            const auto [first, last] = neighbours.equal_range(at);
            for (auto n = first; n != last; ++n)
                if (!bow_parts.count(n->second) && reached.insert(n->second).second)
                    frontier.push_back(n->second);
        }
    }
    std::vector<std::string> points;
    for (const auto& m : model.mats)
        if (reached.count(m.id)) points.push_back(m.id);
    return points;
}

}  // namespace archet
