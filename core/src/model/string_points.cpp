#include "archet/model/string_points.hpp"

#include <map>
#include <set>

namespace archet {

std::vector<std::string> string_points(const Model& model) {
    std::set<std::string> bow_parts, bowed;
    for (const auto& l : model.lias)
        if (l.kind == LiaKind::BowFriction) {
            bow_parts.insert({l.bow(), l.press, l.surface});
            bowed.insert(l.bowed_string());
        }
    std::set<std::string> reached;
    if (bowed.empty()) {
        for (const auto& m : model.mats)
            if (m.kind != MatKind::Gesture) reached.insert(m.id);
    } else {
        std::multimap<std::string, std::string> neighbours;
        for (const auto& l : model.lias) {
            if (l.kind == LiaKind::BowFriction) continue;
            neighbours.emplace(l.from, l.to);
            neighbours.emplace(l.to, l.from);
        }
        std::vector<std::string> frontier(bowed.begin(), bowed.end());
        reached = bowed;
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
