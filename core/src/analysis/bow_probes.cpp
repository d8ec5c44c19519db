#include "archet/analysis/bow_probes.hpp"

#include <algorithm>

namespace archet {

bool read_bow_only(Model& model, std::initializer_list<ProbeKind> kinds) {
    const Lia* bow = first_bow(model);
    if (!bow) return false;
    std::vector<Probe> probes;
    for (ProbeKind kind : kinds) probes.push_back({to_string(kind), kind, bow->id});
    model.probes = std::move(probes);
    return true;
}

}  // namespace archet
