#include "archet/model/linear_system.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <queue>
#include <string_view>
#include <unordered_map>

#include "archet/model/finger_contact.hpp"

namespace archet {

namespace {

bool has_inertia(const Mat& m) {
    return m.kind == MatKind::Mass || m.kind == MatKind::Oscillator;
}

// Builds one level's system: its DOFs, then each link's share of K and Z, in the model's order.
class Assembler {
  public:
    Assembler(const Model& model, const RateLevel& level, LinearSystem& sys)
        : model_(model), level_(level), sys_(sys), dof_(model.mats.size(), -1) {
        // The level's MATs with inertia first, in the model's order; then those of other
        // levels its links reach, as they reach them.
        for (std::size_t i = 0; i < model.mats.size(); ++i)
            if (model.mats[i].rate == level.id) dof_of(i);
        k_.reserve(4 * model.lias.size());
        z_.reserve(4 * model.lias.size());
    }

    void add_links(Fingers fingers) {
        for (const auto& l : model_.lias) {
            if (l.rate != level_.id) continue;
            if (l.kind == LiaKind::Finger) {
                if (fingers == Fingers::Include) add_finger(l);
            } else if (l.kind == LiaKind::BowFriction) {
                couple(mat_index(l.press), mat_index(l.surface), l.stiffness, l.damping);
            } else {
                couple(mat_index(l.from), mat_index(l.to), l.stiffness, l.damping);
            }
        }
        for (std::size_t i = 0; i < model_.mats.size(); ++i) {
            const Mat& m = model_.mats[i];
            if (m.kind == MatKind::Oscillator && m.rate == level_.id)
                couple(i, std::nullopt, m.stiffness, m.damping);
        }
    }

    void finish() {
        const int n = sys_.size();
        sys_.mass.resize(n);
        for (int i = 0; i < n; ++i) sys_.mass[i] = dof_mats_[static_cast<std::size_t>(i)]->mass;
        sys_.stiffness.resize(n, n);
        sys_.damping.resize(n, n);
        sys_.stiffness.setFromTriplets(k_.begin(), k_.end());
        sys_.damping.setFromTriplets(z_.begin(), z_.end());
    }

  private:
    // A MAT as a combination of DOFs: itself, nothing (ground), or for a modal point the modes
    // it reads, weighted by their shapes there.
    using Combination = std::vector<std::pair<int, double>>;

    // MAT `mat`'s DOF, given when first asked for; −1 without inertia.
    int dof_of(std::size_t mat) {
        const Mat& m = model_.mats[mat];
        if (dof_[mat] >= 0 || !has_inertia(m)) return dof_[mat];
        dof_[mat] = static_cast<int>(sys_.dofs.size());
        sys_.dofs.push_back(m.id);
        dof_mats_.push_back(&m);
        return dof_[mat];
    }

    // The MAT of id `id`, by views of the model's own ids (unique in a valid model), looked up
    // in a map made when a link first asks: a level without links (the hand's) needs none.
    std::optional<std::size_t> mat_index(const std::string& id) {
        if (!by_id_) {
            by_id_.emplace();
            by_id_->reserve(model_.mats.size());
            for (std::size_t i = 0; i < model_.mats.size(); ++i)
                by_id_->emplace(model_.mats[i].id, i);
        }
        const auto found = by_id_->find(id);
        if (found == by_id_->end()) return std::nullopt;
        return found->second;
    }

    // Appends MAT `mat`'s combination to `v`, its weights negated or not.
    void append(Combination& v, std::optional<std::size_t> mat, bool negated) {
        if (!mat) return;
        const Mat& m = model_.mats[*mat];
        if (m.kind != MatKind::ModalPoint) {
            if (const int d = dof_of(*mat); d >= 0) v.emplace_back(d, negated ? -1.0 : 1.0);
            return;
        }
        for (std::size_t i = 0; i < m.modes.size() && i < m.weights.size(); ++i)
            if (const auto mode = mat_index(m.modes[i]))
                if (const int d = dof_of(*mode); d >= 0)
                    v.emplace_back(d, negated ? -m.weights[i] : m.weights[i]);
    }

    // A link acting on d = v·x adds value·v·vᵀ, v = a's combination − b's. A MAT met here
    // first takes its DOF then, a's before b's.
    void couple(std::optional<std::size_t> a, std::optional<std::size_t> b, double stiff,
                double damp) {
        v_.clear();  // kept from link to link: no allocation for most of them
        append(v_, a, false);
        append(v_, b, true);
        for (auto [list, value] : {std::pair{&k_, stiff}, std::pair{&z_, damp}}) {
            if (value == 0.0) continue;
            for (auto [i, wi] : v_)
                for (auto [j, wj] : v_) list->emplace_back(i, j, value * wi * wj);
        }
    }

    void add_finger(const Lia& l) {
        const FingerContact at = finger_contact(l.finger_position, l.along.size());
        // The point between the two MATs it lies between, weighted by how near it is to each.
        Combination point, neighbour;
        append(neighbour, mat_index(l.along[at.first]), false);
        for (auto [d, w] : neighbour) point.emplace_back(d, (1 - at.weight) * w);
        neighbour.clear();
        append(neighbour, mat_index(l.along[at.first + 1]), false);
        for (auto [d, w] : neighbour) point.emplace_back(d, at.weight * w);
        sys_.fingers.push_back({point, l.pressure * l.stiffness, l.pressure * l.damping});
    }

    const Model& model_;
    const RateLevel& level_;
    LinearSystem& sys_;
    std::vector<int> dof_;  ///< each MAT's DOF, −1: none (yet)
    std::vector<const Mat*> dof_mats_;
    std::optional<std::unordered_map<std::string_view, std::size_t>> by_id_;
    std::vector<Eigen::Triplet<double>> k_, z_;
    Combination v_;
};

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
    Assembler assembler(model, *level, sys);
    assembler.add_links(fingers);
    assembler.finish();
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

namespace {

bool same_bits(const double* a, const double* b, Eigen::Index count) {
    return count == 0 || std::memcmp(a, b, static_cast<std::size_t>(count) * sizeof(double)) == 0;
}

bool same_bits(const double a, const double b) {
    return same_bits(&a, &b, 1);
}

// The same pattern and the same values, compared compressed (as setFromTriplets() leaves them).
bool same_bits(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
    if (!a.isCompressed() || !b.isCompressed()) {
        Eigen::SparseMatrix<double> ca = a, cb = b;
        ca.makeCompressed(), cb.makeCompressed();
        return same_bits(ca, cb);
    }
    if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
    const auto ints = [](const int* x, const int* y, Eigen::Index n) {
        return n == 0 || std::memcmp(x, y, static_cast<std::size_t>(n) * sizeof(int)) == 0;
    };
    return ints(a.outerIndexPtr(), b.outerIndexPtr(), a.outerSize() + 1) &&
           ints(a.innerIndexPtr(), b.innerIndexPtr(), a.nonZeros()) &&
           same_bits(a.valuePtr(), b.valuePtr(), a.nonZeros());
}

bool same_bits(const FingerTerm& a, const FingerTerm& b) {
    if (a.point.size() != b.point.size() || !same_bits(a.stiffness, b.stiffness) ||
        !same_bits(a.damping, b.damping))
        return false;
    for (std::size_t i = 0; i < a.point.size(); ++i)
        if (a.point[i].first != b.point[i].first ||
            !same_bits(a.point[i].second, b.point[i].second))
            return false;
    return true;
}

}  // namespace

bool is_tridiagonal(const LinearSystem& sys) {
    for (const Eigen::SparseMatrix<double>* m : {&sys.stiffness, &sys.damping})
        for (int column = 0; column < m->outerSize(); ++column)
            for (Eigen::SparseMatrix<double>::InnerIterator it(*m, column); it; ++it)
                if (it.value() != 0.0 && std::abs(it.row() - it.col()) > 1) return false;
    return true;
}

bool identical(const LinearSystem& a, const LinearSystem& b) {
    if (a.rate != b.rate || !same_bits(a.dt, b.dt) || a.dofs != b.dofs ||
        a.mass.size() != b.mass.size() || !same_bits(a.mass.data(), b.mass.data(), a.mass.size()) ||
        !same_bits(a.stiffness, b.stiffness) || !same_bits(a.damping, b.damping) ||
        a.fingers.size() != b.fingers.size())
        return false;
    for (std::size_t i = 0; i < a.fingers.size(); ++i)
        if (!same_bits(a.fingers[i], b.fingers[i])) return false;
    return true;
}

}  // namespace archet
