// Writing and reading a running simulation's parameters by their compiled slots (resolved
// once from ELEMENT.PARAM by CompiledModel::resolve_parameter).

#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/simulation.hpp"
#include "archet/physics/uniform_span.hpp"
#include "archet/physics/unlinked_runs.hpp"

namespace archet {

namespace {

// A finger's field for a slot kind (Z is stored as Z/T, like every damper).
template <class Finger>
auto& finger_field(Finger& f, ParameterSlot::Kind kind) {
    using K = ParameterSlot::Kind;
    return kind == K::FingerK          ? f.k
           : kind == K::FingerZ        ? f.zdt
           : kind == K::FingerPosition ? f.position
                                       : f.pressure;
}

// What follows a change of MAT s's ground: its folded update, its run of alike MATs or of
// unlinked ones.
void ground_changed(CompiledLevel& lv, int s) {
    const bool was_zero_prone = may_leave_negative_zero(lv.update_rest[s]);
    fold_ground(lv, s);
    split_uniform_run(lv, s);
    refolded_unlinked(lv, s, was_zero_prone);
}

// A MAT's mass, with what follows it: T²/m, its folded ground, the modal points' responses.
void set_mass(CompiledLevel& lv, int s, double mass) {
    lv.mass[s] = mass, lv.coeff[s] = lv.dt * lv.dt / mass;
    ground_changed(lv, s);
    for (auto& point : lv.modal_points) point.coeff = modal_point_response(lv, point);
}

}  // namespace

void Simulation::refresh_uniform_runs() {
    for (auto& lv : model_.levels) {
        find_uniform_runs(lv);
        find_chain_lengths(lv);
    }
}

void Simulation::write_slot(const ParameterSlot& s, double v) {
    using K = ParameterSlot::Kind;
    CompiledLevel& lv = model_.levels[s.level];
    switch (s.kind) {
        case K::Mass:
            set_mass(lv, s.index, v);
            break;
        case K::ChainK:
            lv.chain_k[s.index] = v;
            split_uniform_run(lv, s.index);
            break;
        case K::ChainZ:
            lv.chain_zdt[s.index] = v / lv.dt;
            split_uniform_run(lv, s.index);
            break;
        case K::ChainLength: {
            const Lia& l = model_.source.lias[lv.chain_element[s.index]];
            const bool forward = model_.source.mats[lv.element_of[s.index]].id == l.from;
            // + 0.0: a zero length turned around is +0, the bits of none (find_chain_lengths()).
            lv.chain_length[s.index] = (forward ? v : -v) + 0.0;
            lv.has_chain_lengths = lv.has_chain_lengths || v != 0.0;
            split_uniform_run(lv, s.index);
            break;
        }
        case K::LinkK:
            lv.links[s.index].k = v;
            break;
        case K::LinkZ:
            lv.links[s.index].zdt = v / lv.dt;
            break;
        case K::LinkLength:
            lv.links[s.index].length = lv.links[s.index].contact ? -v : v;
            break;
        case K::GroundK:
            lv.ground_k[lv.grounds[s.index].index] = v;
            ground_changed(lv, lv.grounds[s.index].index);
            break;
        case K::GroundZ:
            lv.ground_zdt[lv.grounds[s.index].index] = v / lv.dt;
            ground_changed(lv, lv.grounds[s.index].index);
            break;
        case K::CrossK:
            model_.cross_links[s.index].k = v;
            break;
        case K::CrossZ:
            model_.cross_links[s.index].zdt = v / lv.dt;
            break;
        case K::CrossLength:
            model_.cross_links[s.index].length = model_.cross_links[s.index].contact ? -v : v;
            break;
        case K::BowKb:
            model_.bows[s.index].kb = v;
            break;
        case K::BowZb:
            model_.bows[s.index].zbdt = v / lv.dt;
            break;
        case K::BowMuS:
            model_.bows[s.index].mu_s = v;
            break;
        case K::BowMuD:
            model_.bows[s.index].mu_d = v;
            break;
        case K::BowV0:
            model_.bows[s.index].v0 = v;
            break;
        case K::GesturePositionScale:
            lv.gestures[s.index].position_scale = v;
            break;
        case K::GestureForceScale:
            lv.gestures[s.index].force_scale = v;
            break;
        case K::FixedPosition:  // + 0.0: as the chain loop holds it (hold_fixed_tail())
            for (auto& b : lv.buffer) b[s.index] = v + 0.0;
            break;
        case K::FingerK:
        case K::FingerZ:
        case K::FingerPosition:
        case K::FingerPressure:
            finger_field(model_.fingers[s.index], s.kind) = s.kind == K::FingerZ ? v / lv.dt : v;
            break;
    }
}

double Simulation::read_slot(const ParameterSlot& s) const {
    using K = ParameterSlot::Kind;
    const CompiledLevel& lv = model_.levels[s.level];
    switch (s.kind) {
        case K::Mass:
            return lv.mass[s.index];
        case K::ChainK:
            return lv.chain_k[s.index];
        case K::ChainZ:
            return lv.chain_zdt[s.index] * lv.dt;
        case K::ChainLength: {
            const Lia& l = model_.source.lias[lv.chain_element[s.index]];
            const bool forward = model_.source.mats[lv.element_of[s.index]].id == l.from;
            return forward ? lv.chain_length[s.index] : -lv.chain_length[s.index];
        }
        case K::LinkK:
            return lv.links[s.index].k;
        case K::LinkZ:
            return lv.links[s.index].zdt * lv.dt;
        case K::LinkLength:
            return lv.links[s.index].contact ? -lv.links[s.index].length : lv.links[s.index].length;
        case K::GroundK:
            return lv.ground_k[lv.grounds[s.index].index];
        case K::GroundZ:
            return lv.ground_zdt[lv.grounds[s.index].index] * lv.dt;
        case K::CrossK:
            return model_.cross_links[s.index].k;
        case K::CrossZ:
            return model_.cross_links[s.index].zdt * lv.dt;
        case K::CrossLength: {
            const auto& l = model_.cross_links[s.index];
            return l.contact ? -l.length : l.length;
        }
        case K::BowKb:
            return model_.bows[s.index].kb;
        case K::BowZb:
            return model_.bows[s.index].zbdt * lv.dt;
        case K::BowMuS:
            return model_.bows[s.index].mu_s;
        case K::BowMuD:
            return model_.bows[s.index].mu_d;
        case K::BowV0:
            return model_.bows[s.index].v0;
        case K::GesturePositionScale:
            return lv.gestures[s.index].position_scale;
        case K::GestureForceScale:
            return lv.gestures[s.index].force_scale;
        case K::FixedPosition:
            return lv.x()[s.index];
        case K::FingerK:
        case K::FingerPosition:
        case K::FingerPressure:
            return finger_field(model_.fingers[s.index], s.kind);
        case K::FingerZ:
            return model_.fingers[s.index].zdt * lv.dt;
    }
    return 0;
}

}  // namespace archet
