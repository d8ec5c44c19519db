#include "archet/physics/compiled_model.hpp"

#include <algorithm>
#include <set>
#include <string_view>
#include <unordered_map>

#include "archet/common/input_error.hpp"
#include "archet/model/model_parameters.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/modal_point_position.hpp"
#include "archet/physics/uniform_span.hpp"
#include "derived_points.hpp"

namespace archet {

namespace {

MatSlot slot_of(const CompiledModel& c, const std::string& id) {
    return c.mat_slots.at(id);
}

bool chainable(LiaKind k) {
    return k == LiaKind::Spring || k == LiaKind::Damper || k == LiaKind::SpringDamper;
}

// Runs of storage whose elements follow one another as the storage does, from (storage,
// element) pairs in storage order: a string built in order is one run.
template <class Pairs>
std::vector<ElementRun> element_runs(const Pairs& pairs) {
    std::vector<ElementRun> runs;
    for (const auto& [s, element] : pairs) {
        ElementRun* last = runs.empty() ? nullptr : &runs.back();
        if (last && s == last->end && element == last->element + (s - last->begin))
            ++last->end;
        else
            runs.push_back({s, s + 1, element});
    }
    return runs;
}

void find_element_runs(CompiledLevel& lv) {
    std::vector<std::pair<int, int>> links, grounds;
    for (int j = 1; j < lv.size; ++j)  // links 0 and size are padding
        if (lv.chain_element[j] >= 0) links.emplace_back(j, lv.chain_element[j]);
    for (const CompiledGround& g : lv.grounds) grounds.emplace_back(g.index, g.element);
    lv.chain_element_runs = element_runs(links);
    lv.ground_runs = element_runs(grounds);
}

// A MAT's index in the model by its id: views of the model's own ids, which outlive it.
using MatIndex = std::unordered_map<std::string_view, int>;

// Orders the MATs of one level so that chains of links become consecutive storage, which
// lets the step handle them in one vectorisable loop. Returns model MAT indices in order and
// marks, for each link, whether it became a chain link. `level` holds the ids of the rate
// levels that run at this level's divider.
std::vector<int> order_level(const Model& model, const std::set<std::string>& level,
                             const MatIndex& mat_index, std::vector<bool>& is_chain_link,
                             std::vector<int>& chain_link_after) {
    std::vector<int> mats;
    for (int i = 0; i < static_cast<int>(model.mats.size()); ++i)
        if (level.count(model.mats[i].rate)) mats.push_back(i);
    // Adjacency over chainable same-level links, in model order for determinism.
    std::vector<std::vector<std::pair<int, int>>> adjacent(model.mats.size());  // (neighbour, link)
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
    std::vector<bool> placed(model.mats.size(), false);
    auto walk = [&](int start) {
        int current = start;
        order.push_back(current);
        chain_link_after.push_back(-1);
        placed[current] = true;
        for (;;) {
            int next = -1, via = -1;
            for (auto [neighbour, link] : adjacent[current])
                if (!placed[neighbour] && !is_chain_link[link]) {
                    next = neighbour, via = link;
                    break;
                }
            if (next < 0) return;
            is_chain_link[via] = true;
            chain_link_after.back() = via;
            order.push_back(next);
            chain_link_after.push_back(-1);
            placed[next] = true;
            current = next;
        }
    };
    // Start paths at chain ends (degree ≤ 1) first, then whatever is left (cycles).
    for (int m : mats)
        if (!placed[m] && adjacent[m].size() <= 1) walk(m);
    for (int m : mats)
        if (!placed[m]) walk(m);
    return order;
}

// One compiled level's arrays, its MATs in `order` (chains consecutive, the derived points
// last), each chain link stored with the MAT before it.
void fill_level(CompiledModel& c, const Model& model, int li, const std::vector<int>& order,
                const std::vector<int>& chain_link_after, const std::vector<bool>& derived) {
    CompiledLevel& lv = c.levels[li];
    lv.size = static_cast<int>(order.size());
    const int storage = lv.size + 2;
    // What the chain loop reads or writes, with the zeros it runs into past the last MAT.
    for (auto* values : {&lv.buffer[0], &lv.buffer[1], &lv.buffer[2], &lv.coeff, &lv.chain_k,
                         &lv.chain_zdt, &lv.chain_length, &lv.ground_k, &lv.ground_zdt,
                         &lv.ground_rest, &lv.update_x, &lv.update_xp, &lv.update_rest})
        values->assign(storage + CompiledLevel::kReadAhead, 0.0);
    lv.mass.assign(storage, 0.0);
    lv.external.assign(storage, 0.0);
    lv.held.assign(storage, 0.0);
    lv.chain_force.assign(storage, 0.0);
    lv.chain_element.assign(storage, -1);
    lv.element_of.assign(storage, -1);
    lv.modal_point_of.assign(storage, -1);
    lv.derived_point_of.assign(storage, -1);
    for (int k = 0; k < lv.size; ++k) {
        const int s = k + 1;
        const Mat& m = model.mats[order[k]];
        c.mat_slots[m.id] = {li, s};
        lv.element_of[s] = order[k];
        const bool movable = m.kind == MatKind::Mass || m.kind == MatKind::Oscillator;
        lv.mass[s] = movable ? m.mass : 0.0;
        lv.coeff[s] = movable ? lv.dt * lv.dt / m.mass : 0.0;
        // Initial state: x[0] = position, x[−1] = position − velocity·T.
        lv.x()[s] = m.position;
        lv.x_prev()[s] = movable ? m.position - m.velocity * lv.dt : m.position;
        const bool held = m.kind == MatKind::Fixed || derived[order[k]];
        lv.fixed_after = held ? lv.fixed_after + 1 : 0;
        lv.derived_after += derived[order[k]];
        if (m.kind == MatKind::Oscillator) {
            lv.grounds.push_back({s, order[k]});
            lv.ground_k[s] = m.stiffness, lv.ground_zdt[s] = m.damping / lv.dt;
            lv.ground_rest[s] = m.position;
        }
        if (m.kind == MatKind::Gesture) {
            lv.watched.push_back(s);
            lv.gestures.push_back({s, m.axis, m.position_scale, m.force_scale, order[k],
                                   static_cast<int>(lv.watched.size()) - 1});
        }
        const int link = chain_link_after[k];
        if (link >= 0) {
            const Lia& l = model.lias[link];
            // The chain computes d = x[s] − x[s+1]; flip the sign when the link runs the
            // other way so that its length keeps its meaning.
            const bool forward = l.from == m.id;
            lv.chain_k[s] = l.stiffness;
            lv.chain_zdt[s] = l.damping / lv.dt;
            lv.chain_length[s] =
                (forward ? l.length : -l.length) + 0.0;  // never −0, see write_slot()
            lv.has_chain_lengths = lv.has_chain_lengths || l.length != 0.0;
            lv.chain_element[s] = link;
        }
    }
    hold_fixed_tail(lv);
    fold_grounds(lv);
    lv.unlinked = find_unlinked_runs(lv);
    find_uniform_runs(lv);
    find_element_runs(lv);
}

// Rate levels that share a divider tick together: they compile into one level, so links
// between them are ordinary links rather than rate crossings. Fastest first.
void compile_levels(CompiledModel& c, const Model& model, std::map<std::string, int>& level_index,
                    std::vector<bool>& is_chain_link, const std::vector<bool>& derived) {
    MatIndex mat_index;
    mat_index.reserve(model.mats.size());
    for (int i = 0; i < static_cast<int>(model.mats.size()); ++i) mat_index[model.mats[i].id] = i;
    c.mat_slots.reserve(model.mats.size());
    std::map<int, std::set<std::string>> by_divider;
    for (const auto& r : model.rates) by_divider[r.divider].insert(r.id);
    for (const auto& [divider, ids] : by_divider) {
        const int li = static_cast<int>(c.levels.size());
        CompiledLevel& lv = c.levels.emplace_back();
        for (const auto& r : model.rates)  // named in the model's order
            if (ids.count(r.id)) level_index[r.id] = li, lv.id += (lv.id.empty() ? "" : "+") + r.id;
        lv.divider = divider;
        lv.inverse_divider = 1.0 / divider;
        lv.dt = divider / c.sample_rate;
        std::vector<int> chain_link_after;
        std::vector<int> order =
            order_level(model, ids, mat_index, is_chain_link, chain_link_after);
        hold_derived_points_last(order, chain_link_after, derived);
        fill_level(c, model, li, order, chain_link_after, derived);
    }
}

void compile_modal_points(CompiledModel& c, const Model& model, const std::vector<bool>& derived) {
    for (std::size_t i = 0; i < model.mats.size(); ++i) {
        const Mat& m = model.mats[i];
        if (m.kind != MatKind::ModalPoint) continue;
        const MatSlot p = slot_of(c, m.id);
        CompiledLevel& lv = c.levels[p.level];
        CompiledModalPoint point;
        point.index = p.index;
        point.weights = m.weights;
        for (const auto& mode : m.modes) point.modes.push_back(slot_of(c, mode).index);
        bool in_order = !point.modes.empty();
        for (std::size_t k = 1; k < point.modes.size(); ++k)
            in_order = in_order && point.modes[k] == point.modes[0] + static_cast<int>(k);
        point.first_mode = in_order ? point.modes[0] : -1;
        if (derived[i]) {  // held where it is now
            const double position = modal_point_position(point, lv.x()) + 0.0;
            for (auto& buffer : lv.buffer) buffer[p.index] = position;
            lv.derived_point_of[p.index] = static_cast<int>(lv.derived_points.size());
            lv.derived_points.push_back(std::move(point));
            continue;
        }
        // A modal point has no position of its own: it is where its modes put it.
        lv.x()[p.index] = modal_point_position(point, lv.x());
        lv.x_prev()[p.index] = modal_point_position(point, lv.x_prev());
        point.coeff = modal_point_response(lv, point);
        lv.modal_point_of[p.index] = static_cast<int>(lv.modal_points.size());
        lv.modal_points.push_back(std::move(point));
    }
}

int gesture_point(const CompiledModel& c, MatSlot s) {
    const auto& gestures = c.levels[s.level].gestures;
    for (int i = 0; i < static_cast<int>(gestures.size()); ++i)
        if (gestures[i].index == s.index) return i;
    return -1;
}

// A link between two compiled levels, weighted by their rates; a spring from a slower
// gesture point is a hand link.
CompiledCrossLink cross_link(const CompiledModel& c, int li, int level, MatSlot a, MatSlot b,
                             double k, double zdt, double length, bool contact) {
    CompiledCrossLink x;
    x.level = level, x.a = a, x.b = b;
    x.k = k, x.zdt = zdt, x.length = length, x.contact = contact;
    x.element = li;
    const int link_div = c.levels[level].divider;
    const int a_div = c.levels[a.level].divider, b_div = c.levels[b.level].divider;
    using R = CompiledCrossLink::EndRate;
    auto rate = [&](int div) {
        return div == link_div ? R::Same : div < link_div ? R::Faster : R::Slower;
    };
    x.a_rate = rate(a_div), x.b_rate = rate(b_div);
    x.a_weight = x.a_rate == R::Slower ? static_cast<double>(link_div) / a_div : 1.0;
    x.b_weight = x.b_rate == R::Slower ? static_cast<double>(link_div) / b_div : 1.0;
    x.d_prev = c.levels[a.level].x()[a.index] - c.levels[b.level].x()[b.index];
    const int hand_at_a = x.a_rate == R::Slower ? gesture_point(c, a) : -1;
    const int hand_at_b = x.b_rate == R::Slower ? gesture_point(c, b) : -1;
    if (!contact && hand_at_a >= 0 && x.b_rate == R::Same)
        x.hand = hand_at_a, x.hand_is_a = true, x.hand_slot = a, x.end_slot = b;
    if (!contact && hand_at_b >= 0 && x.a_rate == R::Same)
        x.hand = hand_at_b, x.hand_is_a = false, x.hand_slot = b, x.end_slot = a;
    x.hand_sign = x.hand_is_a ? 1.0 : -1.0;
    return x;
}

CompiledBow compile_bow(const CompiledModel& c, const Lia& l, int li, int level, double dt) {
    CompiledBow bow;
    bow.level = level;
    bow.bow = slot_of(c, l.bow()).index, bow.string = slot_of(c, l.bowed_string()).index;
    bow.press = slot_of(c, l.press).index, bow.surface = slot_of(c, l.surface).index;
    bow.kb = l.buffer_stiffness(), bow.zbdt = l.buffer_damping() / dt;
    bow.mu_s = l.mu_static, bow.mu_d = l.mu_dynamic, bow.v0 = l.v0;
    bow.element = li;
    return bow;
}

// Every link not in a chain: bows, same-level links and links across levels.
void compile_links(CompiledModel& c, const Model& model,
                   const std::map<std::string, int>& level_index,
                   const std::vector<bool>& is_chain_link) {
    auto touch = [&](MatSlot s) { c.levels[s.level].touched.push_back(s.index); };
    for (int li = 0; li < static_cast<int>(model.lias.size()); ++li) {
        const Lia& l = model.lias[li];
        if (is_chain_link[li]) continue;
        const int level = level_index.at(l.rate);
        const double dt = c.levels[level].dt;
        if (l.kind == LiaKind::BowFriction) {
            for (const auto* id : {&l.from, &l.to, &l.press, &l.surface}) touch(slot_of(c, *id));
            c.levels[level].bows.push_back(static_cast<int>(c.bows.size()));
            c.bows.push_back(compile_bow(c, l, li, level, dt));
            continue;
        }
        if (l.kind == LiaKind::Finger) {  // acts on the new positions, like the bow
            CompiledFinger f{level,      {}, l.stiffness, l.damping / dt, l.finger_position,
                             l.pressure, li};
            for (const auto& id : l.along) f.along.push_back(slot_of(c, id).index);
            c.levels[level].fingers.push_back(static_cast<int>(c.fingers.size()));
            c.fingers.push_back(std::move(f));
            continue;
        }
        const bool contact = l.kind == LiaKind::Buffer;
        // A buffer with gap g acts while x(to) − x(from) < g, i.e. d − (−g) > 0.
        const double length = contact ? -l.gap() : l.length;
        const MatSlot a = slot_of(c, l.from), b = slot_of(c, l.to);
        touch(a), touch(b);
        if (a.level == level && b.level == level)  // same compiled level
            c.levels[level].links.push_back(
                {a.index, b.index, l.stiffness, l.damping / dt, length, contact, li});
        else
            c.cross_links.push_back(
                cross_link(c, li, level, a, b, l.stiffness, l.damping / dt, length, contact));
    }
    // Hand links first: they have a short path of their own in the simulation.
    std::stable_partition(c.cross_links.begin(), c.cross_links.end(),
                          [](const CompiledCrossLink& l) { return l.hand >= 0; });
    c.hand_links = static_cast<int>(std::count_if(c.cross_links.begin(), c.cross_links.end(),
                                                  [](const auto& l) { return l.hand >= 0; }));
}

// Probes and outputs, with the forces the levels must keep for them.
void compile_readouts(CompiledModel& c, const Model& model) {
    auto watch = [&](MatSlot s) {
        auto& w = c.levels[s.level].watched;
        auto it = std::find(w.begin(), w.end(), s.index);
        if (it != w.end()) return static_cast<int>(it - w.begin());
        w.push_back(s.index);
        return static_cast<int>(w.size() - 1);
    };
    for (const auto& p : model.probes) {
        CompiledProbe cp;
        cp.id = p.id;
        cp.kind = p.kind;
        if (p.kind == ProbeKind::Position || p.kind == ProbeKind::Velocity ||
            p.kind == ProbeKind::Force)
            cp.mat = slot_of(c, p.element);
        if (p.kind == ProbeKind::Force) cp.watched = watch(cp.mat);
        if (p.kind == ProbeKind::NormalForce || p.kind == ProbeKind::FrictionForce ||
            p.kind == ProbeKind::SlipVelocity)
            for (int b = 0; b < static_cast<int>(c.bows.size()); ++b)
                if (model.lias[c.bows[b].element].id == p.element) cp.bow = b;
        c.probes.push_back(cp);
    }
    for (const auto& o : model.outputs) {
        CompiledOutput co{slot_of(c, o.element), o.signal, o.gain, -1};
        if (o.signal == Output::Signal::Force) co.watched = watch(co.mat);
        c.outputs.push_back(co);
    }
    for (auto& lv : c.levels) {
        std::sort(lv.touched.begin(), lv.touched.end());
        lv.touched.erase(std::unique(lv.touched.begin(), lv.touched.end()), lv.touched.end());
        lv.watched_force.assign(lv.watched.size(), 0.0);
        // The watched MATs' totals need their chain links.
        std::set<int> used;
        for (int s : lv.watched) used.insert({s - 1, s});
        lv.chain_forces_used.assign(used.begin(), used.end());
    }
}

}  // namespace

void hold_fixed_tail(CompiledLevel& lv) {
    for (int s = lv.size - lv.fixed_after + 1; s <= lv.size; ++s) {
        // + 0.0: 2x − x⁻ + 0·F, the loop's update of a fixed MAT, is x but never −0.
        const double position = lv.x()[s] + 0.0;
        for (auto& buffer : lv.buffer) buffer[s] = position;
    }
}

void find_chain_lengths(CompiledLevel& lv) {
    lv.has_chain_lengths = std::any_of(lv.chain_length.begin(), lv.chain_length.end(),
                                       [](double length) { return length != 0.0; });
}

double modal_point_response(const CompiledLevel& lv, const CompiledModalPoint& point) {
    double response = 0;
    for (std::size_t k = 0; k < point.modes.size(); ++k)
        response += point.weights[k] * point.weights[k] * lv.coeff[point.modes[k]];
    return response;
}

namespace {

// Which modal points a force on each one moves: those sharing its modes, the others being
// where their modes are already, as every force on a plain mass a point reads is followed by
// all the points following their modes (integrate(), and after a finger's or a bow's pushes).
void plan_modal_moves(CompiledModel& c) {
    for (CompiledLevel& lv : c.levels) {
        lv.read_by_point.assign(lv.modal_point_of.size(), 0);
        for (const CompiledModalPoint& p : lv.modal_points)
            for (int mode : p.modes) lv.read_by_point[mode] = 1;
        const auto shares_a_mode = [](const CompiledModalPoint& p, const CompiledModalPoint& q) {
            return std::any_of(p.modes.begin(), p.modes.end(), [&](int mode) {
                return std::find(q.modes.begin(), q.modes.end(), mode) != q.modes.end();
            });
        };
        for (CompiledModalPoint& p : lv.modal_points) {
            p.moving_with.clear();
            for (std::size_t q = 0; q < lv.modal_points.size(); ++q)
                if (shares_a_mode(p, lv.modal_points[q]))
                    p.moving_with.push_back(static_cast<int>(q));
        }
    }
}

}  // namespace

CompiledModel compile(const Model& model, double sample_rate) {
    CompiledModel c;
    c.source = model;
    c.sample_rate = sample_rate > 0 ? sample_rate : model.sample_rate;
    c.output_gain = model.output_gain;
    std::map<std::string, int> level_index;
    std::vector<bool> is_chain_link(model.lias.size(), false);
    const std::vector<bool> derived = find_derived_points(model);
    compile_levels(c, model, level_index, is_chain_link, derived);
    compile_modal_points(c, model, derived);
    compile_links(c, model, level_index, is_chain_link);
    plan_modal_moves(c);
    compile_readouts(c, model);
    for (const auto& ctl : model.controls) {
        CompiledControl cc;
        cc.source = ctl.source;
        cc.level = level_index.at(ctl.rate);
        cc.envelope = ctl.envelope;
        cc.axis = ctl.axis;
        if (ctl.source == Control::Source::Position) cc.position_of = slot_of(c, ctl.element);
        cc.gain = ctl.gain, cc.offset = ctl.offset, cc.minimum = ctl.minimum,
        cc.maximum = ctl.maximum;
        cc.target = c.resolve_parameter(ctl.target);
        c.controls.push_back(cc);
    }
    return c;
}

const CompiledLevel* hand_level(const CompiledModel& model) {
    const CompiledLevel* slowest = nullptr;
    for (const auto& level : model.levels)
        if (!level.gestures.empty() && (!slowest || level.divider >= slowest->divider))
            slowest = &level;
    return slowest;
}

// The table (element_kinds.cpp) says which parameters a kind has and what each is to the
// physics; here a role finds its slot in the arrays the element was compiled into.
ParameterSlot CompiledModel::resolve_parameter(const ParameterName& name) const {
    using K = ParameterSlot::Kind;
    using R = ParameterRole;
    const std::string where = name.text();
    const R role = parameter_role(source, name);  // throws for unknown elements and names
    if (const Mat* m = source.find_mat(name.element)) {
        const MatSlot s = mat_slots.at(name.element);
        const CompiledLevel& lv = levels[s.level];
        auto find_in = [&](const auto& list) {
            for (int i = 0; i < static_cast<int>(list.size()); ++i)
                if (list[i].index == s.index) return i;
            return -1;
        };
        if (role == R::Mass) return {K::Mass, s.level, s.index};
        if (role == R::Stiffness || role == R::Damping)  // an oscillator's, to ground
            return {role == R::Stiffness ? K::GroundK : K::GroundZ, s.level, find_in(lv.grounds)};
        if (role == R::PositionScale || role == R::ForceScale)
            return {role == R::PositionScale ? K::GesturePositionScale : K::GestureForceScale,
                    s.level, find_in(lv.gestures)};
        if (m->kind == MatKind::Fixed && role == R::Position)
            return {K::FixedPosition, s.level, s.index};
        throw InputError(where, "is an initial condition and cannot change while the model runs");
    }
    const int li = static_cast<int>(source.find_lia(name.element) - source.lias.data());
    for (int b = 0; b < static_cast<int>(bows.size()); ++b) {
        if (bows[b].element != li) continue;
        const std::map<R, K> kinds{{R::Stiffness, K::BowKb},
                                   {R::Damping, K::BowZb},
                                   {R::MuStatic, K::BowMuS},
                                   {R::MuDynamic, K::BowMuD},
                                   {R::V0, K::BowV0}};
        return {kinds.at(role), bows[b].level, b};
    }
    for (int f = 0; f < static_cast<int>(fingers.size()); ++f) {
        if (fingers[f].element != li) continue;
        const std::map<R, K> kinds{{R::Stiffness, K::FingerK},
                                   {R::Damping, K::FingerZ},
                                   {R::FingerPosition, K::FingerPosition},
                                   {R::Pressure, K::FingerPressure}};
        return {kinds.at(role), fingers[f].level, f};
    }
    const bool is_k = role == R::Stiffness, is_z = role == R::Damping;
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
