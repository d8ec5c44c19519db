#include "archet/model/string_points.hpp"

#include <algorithm>
#include <map>
#include <set>

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
}  // namespace

std::string bowed_centre(const Model& model, const Lia& bow) {
    const Mat* end = model.find_mat(bow.bowed_string());
    if (!end || !is_contact_point(model, *end)) return bow.bowed_string();
    std::size_t best = 0;
    for (std::size_t k = 0; k < end->modes.size() && k < end->weights.size(); ++k)
        if (end->weights[k] > end->weights[best]) best = k;
    return end->modes[best];
}

std::vector<std::string> string_points(const Model& model) {
    std::set<std::string> bow_parts, bowed;
    for (const auto& l : model.lias)
        if (l.kind == LiaKind::BowFriction) {
            bow_parts.insert({l.bow(), l.press, l.surface});
            bowed.insert(bowed_centre(model, l));
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
            if (m.kind == MatKind::ModalPoint &&
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
