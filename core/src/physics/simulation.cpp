#include "archet/physics/simulation.hpp"

#include "archet/common/scheme_revision.hpp"
#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/modal_point_position.hpp"
#include "friction_solve.hpp"
#include "hand_link_tick.hpp"
#include "level_forces.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace archet {

namespace {

double envelope_at(const std::vector<std::pair<double, double>>& e, double t) {
    if (t <= e.front().first) return e.front().second;
    if (t >= e.back().first) return e.back().second;
    auto it = std::upper_bound(e.begin(), e.end(), t,
                               [](double v, const auto& p) { return v < p.first; });
    const auto& b = *it;
    const auto& a = *(it - 1);
    return a.second + (t - a.first) / (b.first - a.first) * (b.second - a.second);
}
}  // namespace

Simulation::Simulation(CompiledModel model)
    : model_(std::move(model)), chain_build_(chosen_chain_build()) {
    active_.assign(model_.levels.size(), 0);
    countdown_.assign(model_.levels.size(), 0);
    period_done_.assign(model_.levels.size(), 1.0);
    // The hand links' addresses, resolved once: model_ never changes shape from here on.
    for (int i = 0; i < model_.hand_links; ++i) {
        CompiledCrossLink& l = model_.cross_links[i];
        CompiledLevel& hand = model_.levels[l.hand_slot.level];
        CompiledLevel& end = model_.levels[l.end_slot.level];
        hand_plan_.push_back({&l, &hand, &end, l.hand_slot.level, l.hand_slot.index,
                              l.end_slot.index, &end.external[l.end_slot.index],
                              &hand.external[l.hand_slot.index], &hand.gestures[l.hand],
                              l.hand_is_a ? l.a_weight : l.b_weight});
    }
    dissipated_.assign(model_.source.lias.size() + model_.source.mats.size(), 0.0);
    bowed_chain_ = bowed_chain_shape_misfit().empty();
    set_gesture_track(model_.source.gesture ? &*model_.source.gesture : nullptr);
}

void Simulation::set_gesture_track(const Gesture* gesture) {
    track_ = gesture;
    // Gesture points start at rest where the gesture starts.
    for (auto& level : model_.levels)
        for (auto& g : level.gestures) {
            const double x = g.position_scale * gesture_axis(g.axis, time());
            level.x()[g.index] = x;
            level.x_prev()[g.index] = x;
        }
    for (auto& link : model_.cross_links) {
        const double a = seen_position(link.a, link.a_rate, true);
        const double b = seen_position(link.b, link.b_rate, true);
        link.d_prev = link.d_before = a - b;
        link.hand_seen = link.hand_is_a ? a : b;
        link.hand_force_sum = link.hand_work_sum = 0.0;
    }
}

double Simulation::gesture_axis(GestureAxis axis, double t) const {
    const GestureSample s = track_ ? track_->at(t) : device_;
    return axis == GestureAxis::Slide ? s.slide : s.press;
}

void Simulation::compute_as_of(int revision) {
    static_assert(kSchemeRevision == 6, "say here how to compute as an older revision, if it can");
    // Revision 5 is a fix (a push reaching the modal points that read its mass): not undone, and
    // render --take says where the older take may differ (scheme_change_since()); so is 6 (the
    // grounds' choice, made when the model is compiled).
    if (revision < 1 || revision > kSchemeRevision)
        throw std::invalid_argument("scheme revision " + std::to_string(revision) +
                                    " is not 1 to " + std::to_string(kSchemeRevision));
    friction_divides_ = revision < 4;
}

void Simulation::enable_accounting(bool on) {
    accounting_ = on;
}

void Simulation::step() {
    // The level arrays once, in locals: the calls below could otherwise change them for all
    // the compiler knows, and it would read them again after each.
    const int levels = static_cast<int>(model_.levels.size());
    CompiledLevel* const level = model_.levels.data();
    const int* const active = active_.data();
    count_down_levels(0);
    if (!model_.controls.empty()) apply_controls();
    // Phase 1: every active LIA computes its force from x[n] (and x[n−1]).
    for (int l = 0; l < levels; ++l)
        if (active[l]) compute_link_forces(level[l]);
    compute_hand_link_forces();
    if (model_.cross_links.size() > static_cast<std::size_t>(model_.hand_links))
        compute_cross_link_forces();
    // Phase 2: every active MAT integrates; the bow modules solve on the prediction.
    for (int l = 0; l < levels; ++l)
        if (active[l]) integrate(level[l]);
    // Phase 3: x[n+1] becomes x[n].
    for (int l = 0; l < levels; ++l)
        if (active[l]) level[l].current = CompiledLevel::after(level[l].current);
    ++tick_;
}

void Simulation::apply_controls() {
    for (const auto& c : model_.controls) {
        if (!active_[c.level]) continue;
        double signal = 0;
        switch (c.source) {
            case Control::Source::Envelope:
                signal = envelope_at(c.envelope, time());
                break;
            case Control::Source::Gesture:
                signal = gesture_axis(c.axis, time());
                break;
            case Control::Source::Position:
                signal = stored_position(c.position_of);
                break;
        }
        write_slot(c.target, std::clamp(c.offset + c.gain * signal, c.minimum, c.maximum));
    }
}

void Simulation::compute_link_forces(CompiledLevel& lv) {
    const double* x = lv.x();
    const double* xp = lv.x_prev();
    double* ext = lv.external.data();
    level_forces::add_link_forces(lv, x, xp, ext);
    // The bow's pressure buffer: its force is the normal force of the friction.
    for (int b : lv.bows) {
        CompiledBow& bow = model_.bows[b];
        bow.normal = friction::pressure_buffer_normal(bow, x, xp);
        ext[bow.press] -= bow.normal;
        ext[bow.surface] += bow.normal;
    }
}

// Hand links: a spring-damper from a slower gesture point to a MAT at the link's rate, the
// usual way to hold a bow. The link sees the hand move along its line and books the hand's
// work itself: F[n]·(x[n+1] − x[n−1])/2 in the scheme's energy, so the move seen now is
// worth the mean of the last two forces (the newest half is pending, see hand_work()).
// Exact at every step, and short: they tick at every step of their level.
void Simulation::compute_hand_link_forces() {
    const int* const active = active_.data();
    const double* const done = period_done_.data();
    const bool accounting = accounting_;
    double hand_work = 0;
    for (HandLinkPlan& p : hand_plan_) {
        CompiledCrossLink& l = *p.link;
        if (!active[l.level]) continue;
        const CompiledLevel& hand = *p.hand_level;
        const double h = hand_link::hand_seen_at(hand.x_prev(), hand.x(), p.hand_index,
                                                 done[p.hand_level_index]);
        const double d_before = l.d_before;
        const hand_link::Tick t = hand_link::tick(l, h, p.end_level->x()[p.end_index]);
        if (accounting)
            dissipated_[l.element] += 0.25 * l.zdt * (t.d - d_before) * (t.d - d_before);
        *p.end_force += t.end_force;
        hand_work += t.work;
        if (active[p.hand_level_index])
            hand_link::hand_over(l, p.hand_weight, *p.hand_force, *p.gesture);
    }
    hand_work_ += hand_work;
}

// Links across rate levels: a link samples its ends at its own ticks (a slower end along its
// line). Its force is held over its period on faster MATs (same impulse) and averaged over
// slower MATs' periods.
void Simulation::compute_cross_link_forces() {
    using R = CompiledCrossLink::EndRate;
    bool faster_ends_ticked = false;
    for (std::size_t i = model_.hand_links; i < model_.cross_links.size(); ++i) {
        CompiledCrossLink& l = model_.cross_links[i];
        if (!active_[l.level]) continue;
        const double d = seen_position(l.a, l.a_rate, false) - seen_position(l.b, l.b_rate, false);
        // The damper of the previous tick has now seen its whole centred motion.
        if (accounting_ && l.acting)
            dissipated_[l.element] += 0.25 * l.zdt * (d - l.d_before) * (d - l.d_before);
        const double f = l.k * (d - l.length) + l.zdt * (d - l.d_prev);
        l.acting = !l.contact || (d - l.length > 0.0 && f > 0.0);
        l.force = l.acting ? f : 0.0;
        l.d_before = l.d_prev;
        l.d_prev = d;
        // An end at the link's rate takes the force now; a slower end takes it weighted by
        // the link's share of its period; faster ends are served below.
        if (l.a_rate != R::Faster)
            model_.levels[l.a.level].external[l.a.index] -= l.a_weight * l.force;
        if (l.b_rate != R::Faster)
            model_.levels[l.b.level].external[l.b.index] += l.b_weight * l.force;
        faster_ends_ticked |= l.a_rate == R::Faster || l.b_rate == R::Faster;
    }
    if (!faster_ends_ticked) return;
    // Faster ends get the force held at each of their ticks until the link's next tick:
    // rebuild those sums now, so that the steps in between cost nothing.
    for (const auto& l : model_.cross_links) {
        if (l.a_rate == R::Faster) model_.levels[l.a.level].held[l.a.index] = 0.0;
        if (l.b_rate == R::Faster) model_.levels[l.b.level].held[l.b.index] = 0.0;
    }
    for (const auto& l : model_.cross_links) {
        if (l.a_rate == R::Faster) model_.levels[l.a.level].held[l.a.index] -= l.force;
        if (l.b_rate == R::Faster) model_.levels[l.b.level].held[l.b.index] += l.force;
    }
}

void Simulation::integrate(CompiledLevel& lv) {
    double* xn = lv.x_next();
    const double* x = lv.x();
    const double* xp = lv.x_prev();
    const double* c = lv.coeff.data();
    double* f = lv.chain_force.data();
    integrate_chain(lv, xn);
    level_forces::recompute_used_chain_forces(lv.chain_forces_used, lv, x, xp, f);
    const double* ext = lv.external.data();
    const double* held = lv.held.data();
    level_forces::add_touched(lv.touched, c, ext, held, xn);
    if (!grounds_in_chain_loop(lv))
        level_forces::pull_grounds(
            lv.grounds, x, xp, c, {lv.ground_k.data(), lv.ground_zdt.data(), lv.ground_rest.data()},
            xn);
    if (!lv.modal_points.empty())
        level_forces::move_modal_points(lv.modal_points, c, ext, held, xn);
    for (int f : lv.fingers) solve_finger(lv, model_.fingers[f]);
    for (int b : lv.bows) solve_bow(lv, model_.bows[b]);
    level_forces::sum_watched(lv.watched, ext, held, f, lv.watched_force.data());
    if (!lv.gestures.empty()) update_gesture_points(lv);
    if (accounting_) account(lv);
    level_forces::clear_touched(lv.touched, lv.external.data());
}

void Simulation::update_modal_points(CompiledLevel& lv) {
    level_forces::follow_modes(lv.modal_points, lv.x_next());
}

void Simulation::apply_modal_force(CompiledLevel& lv, int point, double force) {
    double* xn = lv.x_next();
    const CompiledModalPoint& pushed = lv.modal_points[point];
    add_modal_force(pushed, lv.coeff.data(), xn, force);
    for (int q : pushed.moving_with) {  // the others are where their modes are
        const CompiledModalPoint& p = lv.modal_points[q];
        xn[p.index] = modal_point_position(p, xn);
    }
}

void Simulation::update_gesture_points(CompiledLevel& lv) {
    double* xn = lv.x_next();
    const double* xp = lv.x_prev();
    const double t_next = time() + lv.dt;
    for (auto& g : lv.gestures) {
        xn[g.index] = g.position_scale * gesture_axis(g.axis, t_next);
        // The model's force on the point, and the hand's work over this step in the
        // scheme's energy, −F·(x[n+1] − x[n−1])/2, through the links not faster than the
        // point (faster links book theirs at their own ticks).
        g.force = lv.watched_force[g.watched];
        const double work = -0.5 * (g.force - g.faster_links_force) * (xn[g.index] - xp[g.index]);
        hand_work_ += work;
        g.work += work + g.faster_links_work;
        g.power = (work + g.faster_links_work) / lv.dt;
        g.faster_links_force = g.faster_links_work = 0.0;
    }
}

}  // namespace archet
