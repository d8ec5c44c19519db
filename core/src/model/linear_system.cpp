#include "archet/model/linear_system.hpp"

#include <algorithm>
#include <map>
#include <queue>
#include <string_view>
#include <unordered_map>

#include "archet/model/finger_contact.hpp"

namespace archet {

namespace {
bool has_inertia(const Mat& m) {
    return m.kind == MatKind::Mass || m.kind == MatKind::Oscillator;
}
}  // namespace

LinearSystem assemble_linear_system(const Model& model, const std::string& rate_id,
                                    Fingers fingers) {
    const RateLevel* level = nullptr;
    for (const auto& r : model.rates)
        if (rate_id.empty() ? (!level || r.divider < level->divider) : r.id == rate_id) level = &r;
    LinearSystem sys;
    if (!level) return sys;
    sys.rate = level->id;
    sys.dt = level->divider / model.sample_rate;

    // Keyed by views of the model's own ids, which outlive the maps: no id is copied.
    std::unordered_map<std::string_view, const Mat*> mats;
    mats.reserve(model.mats.size());
    for (const auto& m : model.mats) mats.emplace(m.id, &m);
    std::unordered_map<std::string_view, int> index;
    index.reserve(model.mats.size());
    auto dof_of = [&](const std::string& id) -> int {
        const auto found = mats.find(id);
        if (found == mats.end() || !has_inertia(*found->second)) return -1;
        auto [it, added] = index.emplace(id, static_cast<int>(sys.dofs.size()));
        if (added) sys.dofs.push_back(id);
        return it->second;
    };
    for (const auto& m : model.mats)
        if (m.rate == level->id) dof_of(m.id);

    // A MAT as a combination of DOFs: itself, nothing (ground), or for a modal point the
    // modes it reads, weighted by their shapes there.
    using Combination = std::vector<std::pair<int, double>>;
    auto combination = [&](const std::string& id) -> Combination {
        const auto found = mats.find(id);
        if (found == mats.end()) return {};
        const Mat& m = *found->second;
        if (m.kind != MatKind::ModalPoint) {
            const int d = dof_of(id);
            return d >= 0 ? Combination{{d, 1.0}} : Combination{};
        }
        Combination c;
        for (std::size_t i = 0; i < m.modes.size() && i < m.weights.size(); ++i)
            if (const int d = dof_of(m.modes[i]); d >= 0) c.emplace_back(d, m.weights[i]);
        return c;
    };
    std::vector<Eigen::Triplet<double>> k, z;
    // A link acting on d = v·x adds value·v·vᵀ, v = combination(a) − combination(b).
    auto couple = [&](const Combination& a, const Combination& b, double stiff, double damp) {
        Combination v = a;
        for (auto [d, w] : b) v.emplace_back(d, -w);
        for (auto [list, value] : {std::pair{&k, stiff}, std::pair{&z, damp}}) {
            if (value == 0.0) continue;
            for (auto [i, wi] : v)
                for (auto [j, wj] : v) list->emplace_back(i, j, value * wi * wj);
        }
    };
    for (const auto& l : model.lias) {
        if (l.rate != level->id) continue;
        if (l.kind == LiaKind::BowFriction) {
            couple(combination(l.press), combination(l.surface), l.stiffness, l.damping);
        } else if (l.kind == LiaKind::Finger) {
            if (fingers == Fingers::Exclude) continue;
            const FingerContact at = finger_contact(l.finger_position, l.along.size());
            Combination point;
            for (auto [d, w] : combination(l.along[at.first]))
                point.emplace_back(d, (1 - at.weight) * w);
            for (auto [d, w] : combination(l.along[at.first + 1]))
                point.emplace_back(d, at.weight * w);
            sys.fingers.push_back({point, l.pressure * l.stiffness, l.pressure * l.damping});
        } else {
            couple(combination(l.from), combination(l.to), l.stiffness, l.damping);
        }
    }
    for (const auto& m : model.mats)
        if (m.kind == MatKind::Oscillator && m.rate == level->id)
            couple(combination(m.id), {}, m.stiffness, m.damping);

    const int n = sys.size();
    sys.mass.resize(n);
    for (int i = 0; i < n; ++i) sys.mass[i] = mats.at(sys.dofs[i])->mass;
    sys.stiffness.resize(n, n);
    sys.damping.resize(n, n);
    sys.stiffness.setFromTriplets(k.begin(), k.end());
    sys.damping.setFromTriplets(z.begin(), z.end());
    return sys;
}

LinearSystem connected_part(const LinearSystem& sys, const std::string& dof) {
    const auto found = std::find(sys.dofs.begin(), sys.dofs.end(), dof);
    if (found == sys.dofs.end()) return sys;
    const int n = sys.size();
    const Eigen::SparseMatrix<double> coupling = sys.stiffness + sys.damping;
    std::vector<int> keep;
    std::vector<bool> seen(n, false);
    std::queue<int> todo;
    todo.push(static_cast<int>(found - sys.dofs.begin()));
    seen[todo.front()] = true;
    while (!todo.empty()) {
        const int i = todo.front();
        todo.pop();
        keep.push_back(i);
        for (Eigen::SparseMatrix<double>::InnerIterator it(coupling, i); it; ++it)
            if (!seen[it.row()] && it.value() != 0.0)
                seen[it.row()] = true, todo.push(static_cast<int>(it.row()));
    }
    std::sort(keep.begin(), keep.end());
    std::vector<int> position(n, -1);
    for (int k = 0; k < static_cast<int>(keep.size()); ++k) position[keep[k]] = k;
    LinearSystem part;
    part.rate = sys.rate, part.dt = sys.dt;
    part.mass.resize(static_cast<int>(keep.size()));
    for (int k = 0; k < static_cast<int>(keep.size()); ++k) {
        part.dofs.push_back(sys.dofs[keep[k]]);
        part.mass[k] = sys.mass[keep[k]];
    }
    auto restrict = [&](const Eigen::SparseMatrix<double>& full) {
        std::vector<Eigen::Triplet<double>> t;
        for (int col = 0; col < full.outerSize(); ++col)
            for (Eigen::SparseMatrix<double>::InnerIterator it(full, col); it; ++it)
                if (position[it.row()] >= 0 && position[it.col()] >= 0)
                    t.emplace_back(position[it.row()], position[it.col()], it.value());
        Eigen::SparseMatrix<double> m(part.size(), part.size());
        m.setFromTriplets(t.begin(), t.end());
        return m;
    };
    part.stiffness = restrict(sys.stiffness);
    part.damping = restrict(sys.damping);
    for (const FingerTerm& finger : sys.fingers) {
        FingerTerm kept{{}, finger.stiffness, finger.damping};
        for (auto [d, w] : finger.point)
            if (position[d] >= 0) kept.point.emplace_back(position[d], w);
        if (!kept.point.empty()) part.fingers.push_back(std::move(kept));
    }
    return part;
}

LinearSystem sounding_part(const Model& model) {
    const LinearSystem all = assemble_linear_system(model);
    if (model.outputs.empty()) return all;
    return connected_part(all, model.outputs.front().element);
}

}  // namespace archet
