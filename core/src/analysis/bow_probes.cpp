#include "archet/analysis/bow_probes.hpp"

#include <algorithm>

namespace archet {

bool read_bow_only(Model& model, std::initializer_list<ProbeKind> kinds) {
    const auto bow = std::find_if(model.lias.begin(), model.lias.end(),
                                  [](const Lia& l) { return l.kind == LiaKind::BowFriction; });
    if (bow == model.lias.end()) return false;
    std::vector<Probe> probes;
    for (ProbeKind kind : kinds) probes.push_back({to_string(kind), kind, bow->id});
    model.probes = std::move(probes);
    return true;
}

}  // namespace archet
