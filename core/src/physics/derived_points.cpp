#include "derived_points.hpp"

#include <string_view>
#include <unordered_map>

namespace archet {

std::vector<bool> find_derived_points(const Model& model) {
    std::unordered_map<std::string_view, int> mat_index;
    std::vector<bool> derived(model.mats.size(), false);
    for (std::size_t i = 0; i < model.mats.size(); ++i) {
        mat_index[model.mats[i].id] = static_cast<int>(i);
        derived[i] = model.mats[i].kind == MatKind::ModalPoint;
    }
    auto read = [&](const std::string& id) {
        if (const auto found = mat_index.find(id); found != mat_index.end())
            derived[found->second] = false;
    };
    for (const Lia& l : model.lias) {
        for (const std::string* id : {&l.from, &l.to, &l.press, &l.surface}) read(*id);
        for (const std::string& id : l.along) read(id);
    }
    for (const Control& c : model.controls) read(c.element);
    for (const Probe& p : model.probes) read(p.element);
    for (const Output& o : model.outputs) read(o.element);
    return derived;
}

// None is on a chain (no link touches one), so the MATs a chain link joins stay side by side.
void hold_derived_points_last(std::vector<int>& order, std::vector<int>& chain_link_after,
                              const std::vector<bool>& derived) {
    std::vector<int> stepped, stepped_links, last;
    for (std::size_t k = 0; k < order.size(); ++k) {
        if (derived[order[k]]) {
            last.push_back(order[k]);
        } else {
            stepped.push_back(order[k]);
            stepped_links.push_back(chain_link_after[k]);
        }
    }
    stepped_links.resize(stepped_links.size() + last.size(), -1);
    stepped.insert(stepped.end(), last.begin(), last.end());
    order = std::move(stepped);
    chain_link_after = std::move(stepped_links);
}

}  // namespace archet
