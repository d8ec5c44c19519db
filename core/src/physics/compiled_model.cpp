#include "archet/physics/compiled_model.hpp"

#include <algorithm>
#include <set>

#include "archet/common/input_error.hpp"

namespace archet {

namespace {

bool chainable(LiaKind k) {
    return k == LiaKind::Spring || k == LiaKind::Damper || k == LiaKind::SpringDamper;
}

// Orders the MATs of one level so that chains of links become consecutive storage, which
// lets the step handle them in one vectorisable loop. Returns model MAT indices in order and
// marks, for each link, whether it became a chain link. `level` holds the ids of the rate
// levels that run at this level's divider.
std::vector<int> order_level(const Model& model, const std::set<std::string>& level,
                             const std::map<std::string, int>& mat_index,
                             std::vector<bool>& is_chain_link, std::vector<int>& chain_link_after) {
    std::vector<int> mats;
    for (int i = 0; i < static_cast<int>(model.mats.size()); ++i)
        if (level.count(model.mats[i].rate)) mats.push_back(i);
    // Adjacency over chainable same-level links, in model order for determinism.
    std::map<int, std::vector<std::pair<int, int>>> adjacent;  // mat → (neighbour, link)
    for (int li = 0; li < static_cast<int>(model.lias.size()); ++li) {
        const Lia& l = model.lias[li];
        if (!level.count(l.rate) || !chainable(l.kind)) continue;
        const int a = mat_index.at(l.from), b = mat_index.at(l.to);
        if (!level.count(model.mats[a].rate) || !level.count(model.mats[b].rate)) continue;
        // A modal point's force goes to its modes, not through the chain loop.
        if (model.mats[a].kind == MatKind::ModalPoint || model.mats[b].kind == MatKind::ModalPoint)
            continue;
        adjacent[a].push_back({b, li});
        adjacent[b].push_back({a, li});
    }
    std::vector<int> order;
    std::set<int> placed;
    auto walk = [&](int start) {
        int current = start;
        order.push_back(current);
        chain_link_after.push_back(-1);
        placed.insert(current);
        for (;;) {
            int next = -1, via = -1;
            for (auto [neighbour, link] : adjacent[current])
                if (!placed.count(neighbour) && !is_chain_link[link]) {
                    next = neighbour, via = link;
                    break;
                }
            if (next < 0) return;
            is_chain_link[via] = true;
            chain_link_after.back() = via;
            order.push_back(next);
            chain_link_after.push_back(-1);
            placed.insert(next);
            current = next;
        }
    };
    // Start paths at chain ends (degree ≤ 1) first, then whatever is left (cycles).
    for (int m : mats)
        if (!placed.count(m) && adjacent[m].size() <= 1) walk(m);
    for (int m : mats)
        if (!placed.count(m)) walk(m);
    return order;
}

}  // namespace

namespace {

/// compile() in named steps, in the order they must run: levels (storage order and the MATs'
/// initial state), modal points (which read their modes' state), links, then what reads the
/// links' slots (probes, outputs, controls).
class Compiler {
  public:
    Compiler(const Model& model, double sample_rate)
        : model_(model), is_chain_link_(model.lias.size(), false) {
        c_.source = model;
        c_.sample_rate = sample_rate > 0 ? sample_rate : model.sample_rate;
        c_.output_gain = model.output_gain;
        for (int i = 0; i < static_cast<int>(model.mats.size()); ++i)
            mat_index_[model.mats[i].id] = i;
    }

    CompiledModel run() {
        compile_levels();
        compile_modal_points();
        for (int li = 0; li < static_cast<int>(model_.lias.size()); ++li)
            if (!is_chain_link_[li]) compile_link(li);
        // Hand links first: they have a short path of their own in the simulation.
        std::stable_partition(c_.cross_links.begin(), c_.cross_links.end(),
                              [](const CompiledCrossLink& l) { return l.hand >= 0; });
        c_.hand_links = static_cast<int>(std::count_if(c_.cross_links.begin(), c_.cross_links.end(),
                                                       [](const auto& l) { return l.hand >= 0; }));
        for (auto& bow : c_.bows) {
            bow.bow_point = c_.levels[bow.level].modal_point_of[bow.bow];
            bow.string_point = c_.levels[bow.level].modal_point_of[bow.string];
        }
        compile_probes_and_outputs();
        for (auto& lv : c_.levels) {
            std::sort(lv.touched.begin(), lv.touched.end());
            lv.touched.erase(std::unique(lv.touched.begin(), lv.touched.end()), lv.touched.end());
            lv.watched_force.assign(lv.watched.size(), 0.0);
        }
        compile_controls();
        return std::move(c_);
    }

  private:
    // Rate levels that share a divider tick together: they compile into one level, so links
    // between them are ordinary links rather than rate crossings. Fastest first.
    void compile_levels() {
        std::map<int, std::set<std::string>> by_divider;
        for (const auto& r : model_.rates) by_divider[r.divider].insert(r.id);
        for (const auto& [divider, ids] : by_divider) {
            const int li = static_cast<int>(c_.levels.size());
            CompiledLevel& lv = c_.levels.emplace_back();
            for (const auto& r : model_.rates)  // named in the model's order
                if (ids.count(r.id))
                    level_index_[r.id] = li, lv.id += (lv.id.empty() ? "" : "+") + r.id;
            lv.divider = divider;
            lv.inverse_divider = 1.0 / divider;
            lv.dt = divider / c_.sample_rate;
            std::vector<int> chain_link_after;
            const std::vector<int> order =
                order_level(model_, ids, mat_index_, is_chain_link_, chain_link_after);
            lv.size = static_cast<int>(order.size());
            allocate_storage(lv);
            for (int k = 0; k < lv.size; ++k)
                place_mat(lv, li, k + 1, order[k], chain_link_after[k]);
        }
    }

    static void allocate_storage(CompiledLevel& lv) {
        const int storage = lv.size + 2;
        for (auto& b : lv.buffer) b.assign(storage, 0.0);
        for (auto* v : {&lv.coeff, &lv.mass, &lv.external, &lv.held, &lv.chain_k, &lv.chain_zdt,
                        &lv.chain_length, &lv.chain_force})
            v->assign(storage, 0.0);
        for (auto* v : {&lv.chain_element, &lv.element_of, &lv.modal_point_of})
            v->assign(storage, -1);
    }

    /// The MAT `element` at storage slot `s` of level `li`, and the chain link after it.
    void place_mat(CompiledLevel& lv, int li, int s, int element, int link) {
        const Mat& m = model_.mats[element];
        c_.mat_slots[m.id] = {li, s};
        lv.element_of[s] = element;
        const bool movable = m.kind == MatKind::Mass || m.kind == MatKind::Oscillator;
        lv.mass[s] = movable ? m.mass : 0.0;
        lv.coeff[s] = movable ? lv.dt * lv.dt / m.mass : 0.0;
        // Initial state: x[0] = position, x[−1] = position − velocity·T.
        lv.x()[s] = m.position;
        lv.x_prev()[s] = movable ? m.position - m.velocity * lv.dt : m.position;
        if (m.kind == MatKind::Oscillator)
            lv.grounds.push_back({s, m.stiffness, m.damping / lv.dt, m.position, element});
        if (m.kind == MatKind::Gesture) {
            lv.watched.push_back(s);
            lv.gestures.push_back({s, m.axis, m.position_scale, m.force_scale, element,
                                   static_cast<int>(lv.watched.size()) - 1});
        }
        if (link < 0) return;
        const Lia& l = model_.lias[link];
        // The chain computes d = x[s] − x[s+1]; flip the sign when the link runs the other way
        // so that its length keeps its meaning.
        const bool forward = l.from == m.id;
        lv.chain_k[s] = l.stiffness;
        lv.chain_zdt[s] = l.damping / lv.dt;
        lv.chain_length[s] = forward ? l.length : -l.length;
        lv.has_chain_lengths = lv.has_chain_lengths || l.length != 0.0;
        lv.chain_element[s] = link;
    }

    void compile_modal_points() {
        for (const auto& m : model_.mats) {
            if (m.kind != MatKind::ModalPoint) continue;
            const MatSlot p = slot(m.id);
            CompiledLevel& lv = c_.levels[p.level];
            CompiledModalPoint point;
            point.index = p.index;
            point.weights = m.weights;
            for (std::size_t k = 0; k < m.modes.size(); ++k) {
                const int mode = slot(m.modes[k]).index;
                point.modes.push_back(mode);
                point.coeff += m.weights[k] * m.weights[k] * lv.coeff[mode];
                lv.x()[p.index] += m.weights[k] * lv.x()[mode];
                lv.x_prev()[p.index] += m.weights[k] * lv.x_prev()[mode];
            }
            lv.modal_point_of[p.index] = static_cast<int>(lv.modal_points.size());
            lv.modal_points.push_back(std::move(point));
        }
    }

    void compile_link(int li) {
        const Lia& l = model_.lias[li];
        const int level = level_index_.at(l.rate);
        const double dt = c_.levels[level].dt;
        if (l.kind == LiaKind::BowFriction) return compile_bow(li, level, dt);
        const bool contact = l.kind == LiaKind::Buffer;
        // A buffer with gap g acts while x(to) − x(from) < g, i.e. d − (−g) > 0.
        const double length = contact ? -l.length : l.length;
        const MatSlot a = slot(l.from), b = slot(l.to);
        touch(a), touch(b);
        if (a.level == level && b.level == level)  // same compiled level
            c_.levels[level].links.push_back(
                {a.index, b.index, l.stiffness, l.damping / dt, length, contact, li});
        else
            compile_cross_link(li, level, a, b, length, contact);
    }

    void compile_bow(int li, int level, double dt) {
        const Lia& l = model_.lias[li];
        CompiledBow bow;
        bow.level = level;
        bow.bow = slot(l.from).index, bow.string = slot(l.to).index;
        bow.press = slot(l.press).index, bow.surface = slot(l.surface).index;
        bow.kb = l.stiffness, bow.zbdt = l.damping / dt;
        bow.mu_s = l.mu_static, bow.mu_d = l.mu_dynamic, bow.v0 = l.v0;
        bow.element = li;
        for (const auto* id : {&l.from, &l.to, &l.press, &l.surface}) touch(slot(*id));
        c_.levels[level].bows.push_back(static_cast<int>(c_.bows.size()));
        c_.bows.push_back(bow);
    }

    /// A link between MATs of different levels; one whose slower end is a gesture point and
    /// whose other end runs at the link's own rate is a hand link.
    void compile_cross_link(int li, int level, MatSlot a, MatSlot b, double length, bool contact) {
        const Lia& l = model_.lias[li];
        CompiledCrossLink x;
        x.level = level, x.a = a, x.b = b;
        x.k = l.stiffness, x.zdt = l.damping / c_.levels[level].dt, x.length = length;
        x.contact = contact;
        x.element = li;
        const int link_div = c_.levels[level].divider;
        const int a_div = c_.levels[a.level].divider, b_div = c_.levels[b.level].divider;
        using R = CompiledCrossLink::EndRate;
        auto rate = [&](int div) {
            return div == link_div ? R::Same : div < link_div ? R::Faster : R::Slower;
        };
        x.a_rate = rate(a_div), x.b_rate = rate(b_div);
        x.a_weight = x.a_rate == R::Slower ? static_cast<double>(link_div) / a_div : 1.0;
        x.b_weight = x.b_rate == R::Slower ? static_cast<double>(link_div) / b_div : 1.0;
        x.d_prev = c_.levels[a.level].x()[a.index] - c_.levels[b.level].x()[b.index];
        const int hand_at_a = x.a_rate == R::Slower ? gesture_point(a) : -1;
        const int hand_at_b = x.b_rate == R::Slower ? gesture_point(b) : -1;
        if (!contact && hand_at_a >= 0 && x.b_rate == R::Same)
            x.hand = hand_at_a, x.hand_is_a = true, x.hand_slot = a, x.end_slot = b;
        if (!contact && hand_at_b >= 0 && x.a_rate == R::Same)
            x.hand = hand_at_b, x.hand_is_a = false, x.hand_slot = b, x.end_slot = a;
        x.hand_sign = x.hand_is_a ? 1.0 : -1.0;
        c_.cross_links.push_back(x);
    }

    void compile_probes_and_outputs() {
        for (const auto& p : model_.probes) {
            CompiledProbe cp;
            cp.id = p.id;
            cp.kind = p.kind;
            if (p.kind == ProbeKind::Position || p.kind == ProbeKind::Velocity ||
                p.kind == ProbeKind::Force)
                cp.mat = slot(p.element);
            if (p.kind == ProbeKind::Force) cp.watched = watch(cp.mat);
            if (p.kind == ProbeKind::NormalForce || p.kind == ProbeKind::FrictionForce ||
                p.kind == ProbeKind::SlipVelocity)
                for (int b = 0; b < static_cast<int>(c_.bows.size()); ++b)
                    if (model_.lias[c_.bows[b].element].id == p.element) cp.bow = b;
            c_.probes.push_back(cp);
        }
        for (const auto& o : model_.outputs) {
            CompiledOutput co{slot(o.element), o.signal, o.gain, -1};
            if (o.signal == Output::Signal::Force) co.watched = watch(co.mat);
            c_.outputs.push_back(co);
        }
    }

    void compile_controls() {
        for (const auto& ctl : model_.controls) {
            CompiledControl cc;
            cc.source = ctl.source;
            cc.level = level_index_.at(ctl.rate);
            cc.envelope = ctl.envelope;
            cc.axis = ctl.axis;
            if (ctl.source == Control::Source::Position) cc.position_of = slot(ctl.element);
            cc.gain = ctl.gain, cc.offset = ctl.offset, cc.minimum = ctl.minimum,
            cc.maximum = ctl.maximum;
            cc.target = c_.resolve_parameter(ctl.target_element, ctl.target_parameter);
            c_.controls.push_back(cc);
        }
    }

    MatSlot slot(const std::string& id) const { return c_.mat_slots.at(id); }
    void touch(MatSlot s) { c_.levels[s.level].touched.push_back(s.index); }

    int gesture_point(MatSlot s) const {
        const auto& gestures = c_.levels[s.level].gestures;
        for (int i = 0; i < static_cast<int>(gestures.size()); ++i)
            if (gestures[i].index == s.index) return i;
        return -1;
    }

    /// The MAT's slot in its level's watched list (whose forces are kept), added if new.
    int watch(MatSlot s) {
        auto& w = c_.levels[s.level].watched;
        auto it = std::find(w.begin(), w.end(), s.index);
        if (it != w.end()) return static_cast<int>(it - w.begin());
        w.push_back(s.index);
        return static_cast<int>(w.size() - 1);
    }

    const Model& model_;
    CompiledModel c_;
    std::map<std::string, int> mat_index_;
    std::map<std::string, int> level_index_;
    std::vector<bool> is_chain_link_;
};

}  // namespace

CompiledModel compile(const Model& model, double sample_rate) {
    return Compiler(model, sample_rate).run();
}

const CompiledLevel* hand_level(const CompiledModel& model) {
    const CompiledLevel* slowest = nullptr;
    for (const auto& level : model.levels)
        if (!level.gestures.empty() && (!slowest || level.divider >= slowest->divider))
            slowest = &level;
    return slowest;
}

ParameterSlot CompiledModel::resolve_parameter(const std::string& element,
                                               const std::string& name) const {
    using K = ParameterSlot::Kind;
    const std::string where = element + "." + name;
    if (const Mat* m = source.find_mat(element)) {
        const MatSlot s = mat_slots.at(element);
        const CompiledLevel& lv = levels[s.level];
        auto find_in = [&](const auto& list) {
            for (int i = 0; i < static_cast<int>(list.size()); ++i)
                if (list[i].index == s.index) return i;
            return -1;
        };
        if (name == "mass" && (m->kind == MatKind::Mass || m->kind == MatKind::Oscillator))
            return {K::Mass, s.level, s.index};
        if (m->kind == MatKind::Oscillator && (name == "stiffness" || name == "damping"))
            return {name == "stiffness" ? K::GroundK : K::GroundZ, s.level, find_in(lv.grounds)};
        if (m->kind == MatKind::Gesture && (name == "position_scale" || name == "force_scale"))
            return {name == "position_scale" ? K::GesturePositionScale : K::GestureForceScale,
                    s.level, find_in(lv.gestures)};
        if (m->kind == MatKind::Fixed && name == "position")
            return {K::FixedPosition, s.level, s.index};
        if (name == "position" || name == "velocity")
            throw InputError(where,
                             "is an initial condition and cannot change while the model runs");
        throw InputError(where, "is not a parameter of this mass");
    }
    const Lia* l = source.find_lia(element);
    if (!l) throw InputError(where, "no mass or link has this id");
    const int li = static_cast<int>(l - source.lias.data());
    for (int b = 0; b < static_cast<int>(bows.size()); ++b) {
        if (bows[b].element != li) continue;
        const std::map<std::string, K> names{{"buffer_stiffness", K::BowKb},
                                             {"buffer_damping", K::BowZb},
                                             {"mu_s", K::BowMuS},
                                             {"mu_d", K::BowMuD},
                                             {"v0", K::BowV0}};
        auto it = names.find(name);
        if (it == names.end()) break;
        return {it->second, bows[b].level, b};
    }
    const bool length = name == "length" || name == "gap";
    const bool is_k = name == "stiffness", is_z = name == "damping";
    if (!(length || is_k || is_z)) throw InputError(where, "is not a parameter of this link");
    for (int lv = 0; lv < static_cast<int>(levels.size()); ++lv) {
        const auto& level = levels[lv];
        for (int s = 0; s < static_cast<int>(level.chain_element.size()); ++s)
            if (level.chain_element[s] == li)
                return {is_k ? K::ChainK : is_z ? K::ChainZ : K::ChainLength, lv, s};
        for (int i = 0; i < static_cast<int>(level.links.size()); ++i)
            if (level.links[i].element == li)
                return {is_k ? K::LinkK : is_z ? K::LinkZ : K::LinkLength, lv, i};
    }
    for (int i = 0; i < static_cast<int>(cross_links.size()); ++i)
        if (cross_links[i].element == li)
            return {is_k ? K::CrossK : is_z ? K::CrossZ : K::CrossLength, cross_links[i].level, i};
    throw InputError(where, "is not a parameter of this link");
}

}  // namespace archet
