// The state of a running simulation as a flat list of numbers, in one fixed order, so that a
// take started mid-performance can be re-rendered from exactly where it began.

#include <algorithm>
#include <type_traits>

#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/modal_point_position.hpp"
#include "archet/physics/simulation.hpp"
#include "archet/physics/uniform_span.hpp"
#include "archet/physics/unlinked_runs.hpp"

namespace archet {

template <class Self, class Field>
void Simulation::for_each_state(Self& self, Field&& field) {
    auto all = [&](auto& values) {
        for (auto& v : values) field(v);
    };
    field(self.tick_), field(self.hand_work_);
    field(self.device_.slide), field(self.device_.press);
    all(self.active_), all(self.countdown_), all(self.period_done_), all(self.dissipated_);
    for (auto& lv : self.model_.levels) {
        auto stored = [&](auto& values) {  // the storage, not the zeros the chain loop reads ahead
            for (int s = 0; s < lv.size + 2; ++s) field(values[s]);
        };
        field(lv.current);
        for (auto& buffer : lv.buffer) stored(buffer);
        // Parameters may have changed while playing; forces carry over between steps.
        stored(lv.coeff), all(lv.mass), all(lv.external), all(lv.held);
        stored(lv.chain_k), stored(lv.chain_zdt), stored(lv.chain_length);
        stored(lv.chain_force);
        all(lv.watched_force);
        for (auto& l : lv.links) field(l.k), field(l.zdt), field(l.length);
        for (const auto& g : lv.grounds)  // in the order of the grounds, as always
            field(lv.ground_k[g.index]), field(lv.ground_zdt[g.index]),
                field(lv.ground_rest[g.index]);
        for (auto& g : lv.gestures) {
            field(g.position_scale), field(g.force_scale), field(g.force), field(g.work);
            field(g.power), field(g.faster_links_force), field(g.faster_links_work);
        }
        for (auto& p : lv.modal_points) field(p.coeff);
    }
    for (auto& b : self.model_.bows) {
        field(b.kb), field(b.zbdt), field(b.mu_s), field(b.mu_d), field(b.v0);
        field(b.normal), field(b.friction), field(b.slip_velocity), field(b.dissipated);
        field(b.sticking);
    }
    for (auto& f : self.model_.fingers)
        field(f.k), field(f.zdt), field(f.position), field(f.pressure);
    for (auto& l : self.model_.cross_links) {
        field(l.k), field(l.zdt), field(l.length), field(l.d_prev), field(l.force);
        field(l.d_before), field(l.acting), field(l.hand_seen), field(l.hand_force_sum);
        field(l.hand_work_sum);
    }
}

std::size_t Simulation::state_size() const {
    std::size_t n = 0;
    for_each_state(*this, [&](const auto&) { ++n; });
    return n;
}

void Simulation::save_state(double* out) const {
    for_each_state(*this, [&](const auto& v) { *out++ = static_cast<double>(v); });
}

void Simulation::load_state(const double* in) {
    for_each_state(*this,
                   [&](auto& v) { v = static_cast<std::remove_reference_t<decltype(v)>>(*in++); });
    for (auto& lv : model_.levels) {  // the masses, grounds and chain links loaded
        // The zeros the chain loop reads past the storage, which a blown-up run may have left
        // not finite (fastest_chain_build() puts back a state after trials that may blow up).
        for (auto& buffer : lv.buffer) std::fill(buffer.begin() + lv.size + 2, buffer.end(), 0.0);
        hold_fixed_tail(lv);
        fold_grounds(lv);
        recheck_unlinked_runs(lv);
        find_uniform_runs(lv);
        find_chain_lengths(lv);
    }
}

bool Simulation::continue_from(const Simulation& from, std::span<double> scratch) {
    if (from.state_size() != state_size() || scratch.size() != state_size()) return false;
    from.save_state(scratch.data());
    load_state(scratch.data());
    friction_divides_ = from.friction_divides_;
    refresh_modal_points();  // the contact's masses are this compile's
    return true;
}

void Simulation::refresh_modal_points() {
    for (auto& lv : model_.levels)
        for (auto& p : lv.modal_points) {
            p.coeff = modal_point_response(lv, p);
            lv.x()[p.index] = modal_point_position(p, lv.x());
            lv.x_prev()[p.index] = modal_point_position(p, lv.x_prev());
        }
}

}  // namespace archet
