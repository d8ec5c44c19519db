// The step of a bowed chain: what step() does for that one shape, a bowed string (a chain of
// masses at audio rate, with or without grounds, a body or other modal points and links besides
// the chain's, fingers, one bow, a hand holding it through links from slower gesture points), with
// what the general step asks at every tick asked once per block. The same operations in the same
// order, so the same bytes (bowed_chain_test.cpp holds it to step()).
// Built for each instruction set as the chain loop is, with the chain's rounds inlined: the
// build is chosen once per block, not at every tick.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/simulation.hpp"
#include "chain_rounds.hpp"
#include "double_vectors.hpp"
#include "friction_solve.hpp"
#include "hand_link_tick.hpp"
#include "level_forces.hpp"
#include "velocity_run_output.hpp"

namespace archet {

// What keeps the model's shape from a bowed chain's, checked once when it is made: its
// structure never changes after (model() is not for changing it).
std::string Simulation::bowed_chain_shape_misfit() const {
    const CompiledModel& m = model_;
    if (m.levels.empty() || m.levels[0].divider != 1) return "no level runs at the master clock";
    if (!m.controls.empty()) return "it has controls";
    const CompiledLevel& audio = m.levels[0];
    if (!audio.gestures.empty()) return "gesture points run at audio rate";
    if (audio.bows.size() != 1 || m.bows.size() != 1) return "it has no bow, or more than one";
    if (m.hand_links > kMostHandLinks)
        return "more than " + std::to_string(kMostHandLinks) + " hand links hold it";
    if (m.cross_links.size() != static_cast<std::size_t>(m.hand_links))
        return "links join its rate levels besides the hand's";
    for (const CompiledCrossLink& l : m.cross_links)
        if (l.level != 0 || l.end_slot.level != 0 || l.hand_slot.level == 0)
            return "a hand link does not hold a mass at audio rate";
    return "";
}

std::string Simulation::bowed_chain_misfit() const {
    if (!bowed_chain_) return bowed_chain_shape_misfit();
    if (accounting_) return "it keeps energy accounts";
    if (model_.levels[0].has_chain_lengths) return "its chain links have been given rest lengths";
    return "";
}

namespace {

// A hand link's numbers for the length of a block, in the loop's own frame (so that they stay
// in registers rather than being read again after every store of a force), written back after.
struct HandLinkState {
    CompiledCrossLink* link;
    double k, zdt, length, hand_sign, hand_weight;
    bool hand_is_a;
    double d_prev, d_before, force, hand_seen, hand_force_sum, hand_work_sum;
    int end, hand_index, hand_level;
    const CompiledLevel* hand;
    double* hand_force;
    CompiledGesturePoint* gesture;
    /// The hand's previous and newest positions: they change only when its level ticks.
    double from = 0, to = 0;
};

}  // namespace

// What run_bowed_chain() holds over a block: the audio level's arrays, its bow (a copy, written
// back after the block) and its hand links.
struct Simulation::BowedChainFrame {
    CompiledLevel& audio;
    CompiledBow bow;
    int string, bowed, press, surface;
    int mats;  ///< the chain loop's: MATs 1 … mats, before the fixed tail
    double *ext, *chain_forces, *watched_force;
    const double *held, *coeff;
    level_forces::GroundArrays ground;
    const double *chain_k, *chain_zdt, *chain_length, *update_x, *update_xp, *update_rest;
    std::span<const int> touched, forces_used, watched;
    std::span<const CompiledGround> grounds;
    std::span<const CompiledModalPoint> modal_points;
    double string_response, bow_response, dt, inverse_dt;
    bool divides, grounds_in_loop;
    bool body;               ///< links besides the chain's, or modal points
    VelocityRun velocities;  ///< the outputs, when they are such a run
    /// The modal points that nothing reads before the bow's push (neither of the bow's masses,
    /// on no finger's way), a bit each (of the first 64): they follow their modes after it, or
    /// not at all when its push has made them follow (`push_moves_late`, a friction not 0).
    std::uint64_t late = 0;
    bool push_moves_late = false;
    ProbeRows probes;  ///< read after each tick when it has values
    int hands;
    HandLinkState hand[kMostHandLinks];
};

// The ticks of a block, one build per instruction set (W doubles a vector in the chain's
// rounds); a nested class, to reach the simulation's state.
struct Simulation::BowedChainLoop {
    template <int W>
    [[gnu::always_inline]] static std::size_t build(Simulation& sim, BowedChainFrame& frame,
                                                    std::span<double> out);
    template <int W, bool kWithGrounds, bool kWithBody>
    [[gnu::always_inline]] static std::size_t ticks(Simulation& sim, BowedChainFrame& frame,
                                                    std::span<double> out);
    [[gnu::always_inline]] static void hand_links(Simulation& sim, BowedChainFrame& frame,
                                                  const double* x, bool slower);
    /// The hand links into the frame for a block, and back into the model after it (and
    /// before the stored energy is read).
    static void hold_hands(const Simulation& sim, BowedChainFrame& frame);
    [[gnu::always_inline]] static void release_hands(const BowedChainFrame& frame);
    /// read_probe_row() in the loop, inline: a call out of it spills the vector registers the
    /// loop keeps its constants in (that nearly doubled the 110 Hz string's time). The
    /// bow's numbers come from the frame's copy; the stored energy, a sum over the whole model,
    /// is read after the frame is written back.
    [[gnu::always_inline]] static bool read_probes(Simulation& sim, BowedChainFrame& frame,
                                                   std::size_t tick);
    /// Where the hand links' hands are, read again after their levels tick. Inlined into each
    /// build: called out of the AVX-512 loop, its legacy SSE loads ran while the upper halves
    /// of the vector registers were in use (no vzeroupper before the call), which on an Intel
    /// Xeon (Emerald Rapids) cost a seventh of the paper string's time.
    [[gnu::always_inline]] static void read_hands(BowedChainFrame& frame) {
        for (int i = 0; i < frame.hands; ++i) {
            HandLinkState& l = frame.hand[i];
            l.from = l.hand->x_prev()[l.hand_index], l.to = l.hand->x()[l.hand_index];
        }
    }
    /// Which modal points follow their modes only after the bow's push.
    static void plan_late_points(const Simulation& sim, BowedChainFrame& frame);
    [[gnu::always_inline]] static bool is_late(const BowedChainFrame& frame, std::size_t point) {
        return point < 64 && (frame.late >> point & 1u);
    }
    template <int W, bool kWithGrounds, bool kWithBody>
    [[gnu::always_inline]] static void audio_level(Simulation& sim, BowedChainFrame& frame,
                                                   const double* x, const double* xp, double* xn);

    static std::size_t avx512(Simulation& sim, BowedChainFrame& frame, std::span<double> out);
    static std::size_t avx2(Simulation& sim, BowedChainFrame& frame, std::span<double> out);
    static std::size_t plain(Simulation& sim, BowedChainFrame& frame, std::span<double> out);
};

ARCHET_TARGET_AVX512 std::size_t Simulation::BowedChainLoop::avx512(Simulation& sim,
                                                                    BowedChainFrame& frame,
                                                                    std::span<double> out) {
    return build<8>(sim, frame, out);
}

__attribute__((target("avx2"))) std::size_t Simulation::BowedChainLoop::avx2(
    Simulation& sim, BowedChainFrame& frame, std::span<double> out) {
    return build<4>(sim, frame, out);
}

std::size_t Simulation::BowedChainLoop::plain(Simulation& sim, BowedChainFrame& frame,
                                              std::span<double> out) {
    return build<2>(sim, frame, out);
}

std::size_t Simulation::run(std::span<double> out) {
    return run_in(out, chain_build_, {});
}

std::size_t Simulation::run(std::span<double> out, ChainBuild build) {
    if (!chain_build_runs_here(build)) throw std::logic_error("chain build not run here");
    return run_in(out, build, {});
}

std::size_t Simulation::run(std::span<double> out, ProbeRows probes) {
    return run_in(out, chain_build_, probes);
}

void Simulation::set_chain_build(ChainBuild build) {
    if (!chain_build_runs_here(build)) throw std::logic_error("chain build not run here");
    chain_build_ = build;
}

std::size_t Simulation::run_in(std::span<double> out, ChainBuild build, ProbeRows probes) {
    if (out.empty()) return 0;  // (the loop below marks the audio level as ticking)
    if (model_.probes.empty()) probes.values = nullptr;
    if (runs_as_bowed_chain()) return run_bowed_chain(out, build, probes);
    for (std::size_t i = 0; i < out.size(); ++i) {
        step();
        out[i] = output();
        const bool probes_finite = !probes.values || read_probe_row(probes, i);
        if (!std::isfinite(out[i]) || !probes_finite) return i + 1;
    }
    return out.size();
}

// step() for the shape bowed_chain_misfit() accepts: the audio level ticks at every step, its
// one bow solves after its links, grounds, modal points and fingers, and its hand links tick
// with it.
// The slower levels step as in step().
std::size_t Simulation::run_bowed_chain(std::span<double> out, ChainBuild build, ProbeRows probes) {
    CompiledLevel& audio = model_.levels[0];
    const CompiledBow& bow = model_.bows[0];
    BowedChainFrame frame{
        .audio = audio,
        .bow = bow,
        .string = bow.string,
        .bowed = bow.bow,
        .press = bow.press,
        .surface = bow.surface,
        .mats = audio.size - audio.fixed_after,
        .ext = audio.external.data(),
        .chain_forces = audio.chain_force.data(),
        .watched_force = audio.watched_force.data(),
        .held = audio.held.data(),
        .coeff = audio.coeff.data(),
        .ground = {audio.ground_k.data(), audio.ground_zdt.data(), audio.ground_rest.data()},
        .chain_k = audio.chain_k.data(),
        .chain_zdt = audio.chain_zdt.data(),
        .chain_length = audio.chain_length.data(),
        .update_x = audio.update_x.data(),
        .update_xp = audio.update_xp.data(),
        .update_rest = audio.update_rest.data(),
        .touched = audio.touched,
        .forces_used = audio.chain_forces_used,
        .watched = audio.watched,
        .grounds = audio.grounds,
        .modal_points = audio.modal_points,
        .string_response = response(audio, bow.string),
        .bow_response = response(audio, bow.bow),
        .dt = audio.dt,
        .inverse_dt = 1.0 / audio.dt,
        .divides = friction_divides_,
        .grounds_in_loop = grounds_in_chain_loop(audio),
        .body = !audio.links.empty() || !audio.modal_points.empty(),
        .velocities = find_velocity_run(model_),
        .probes = probes,
        .hands = static_cast<int>(hand_plan_.size()),
        .hand = {}};
    BowedChainLoop::hold_hands(*this, frame);
    BowedChainLoop::plan_late_points(*this, frame);
    // What step() writes for a level of divider 1 at every tick.
    active_[0] = 1, countdown_[0] = 0, period_done_[0] = 1.0;
    std::size_t done = 0;
    switch (build) {
        case ChainBuild::Avx512:
            done = BowedChainLoop::avx512(*this, frame, out);
            break;
        case ChainBuild::Avx2:
            done = BowedChainLoop::avx2(*this, frame, out);
            break;
        case ChainBuild::Plain:
            done = BowedChainLoop::plain(*this, frame, out);
            break;
    }
    model_.bows[0] = frame.bow;
    BowedChainLoop::release_hands(frame);
    return done;
}

// The build's ticks, with the level's grounds in the chain's rounds or after them, and with or
// without a body (the paper's string has none, and runs without asking at every tick).
template <int W>
[[gnu::always_inline]] inline std::size_t Simulation::BowedChainLoop::build(Simulation& sim,
                                                                            BowedChainFrame& frame,
                                                                            std::span<double> out) {
    if (frame.body)
        return frame.grounds_in_loop ? ticks<W, true, true>(sim, frame, out)
                                     : ticks<W, false, true>(sim, frame, out);
    return frame.grounds_in_loop ? ticks<W, true, false>(sim, frame, out)
                                 : ticks<W, false, false>(sim, frame, out);
}

template <int W, bool kWithGrounds, bool kWithBody>
[[gnu::always_inline]] inline std::size_t Simulation::BowedChainLoop::ticks(Simulation& sim,
                                                                            BowedChainFrame& frame,
                                                                            std::span<double> out) {
    const int levels = static_cast<int>(sim.model_.levels.size());
    CompiledLevel* const level = sim.model_.levels.data();
    CompiledLevel& audio = frame.audio;
    const int* const active = sim.active_.data();
    std::size_t done = 0;
    while (done < out.size()) {
        // Most ticks, no slower level ticks (the hand's, at the default divider, every 16th).
        const bool slower = sim.count_down_levels(1);
        const int now = audio.current;
        const double* const x = audio.buffer[now].data();
        const double* const xp = audio.buffer[CompiledLevel::before(now)].data();
        double* const xn = audio.buffer[CompiledLevel::after(now)].data();
        // Phase 1: the audio level's links, then its bow's pressure buffer; the slower levels'
        // links; the hand links.
        if constexpr (kWithBody) level_forces::add_link_forces(audio, x, xp, frame.ext);
        const double normal = friction::pressure_buffer_normal(frame.bow, x, xp);
        frame.bow.normal = normal;
        frame.ext[frame.press] -= normal;
        frame.ext[frame.surface] += normal;
        if (slower)
            for (int l = 1; l < levels; ++l)
                if (active[l]) sim.compute_link_forces(level[l]);
        hand_links(sim, frame, x, slower);
        // Phase 2: the audio level, then the slower levels; phase 3: x[n+1] becomes x[n].
        audio_level<W, kWithGrounds, kWithBody>(sim, frame, x, xp, xn);
        if (slower) {
            for (int l = 1; l < levels; ++l)
                if (active[l]) sim.integrate(level[l]);
            for (int l = 1; l < levels; ++l)
                if (active[l]) level[l].current = CompiledLevel::after(level[l].current);
            read_hands(frame);
        }
        audio.current = CompiledLevel::after(now);
        ++sim.tick_;
        const double sample = frame.velocities.count > 0
                                  ? velocity_run_output::sound<W>(frame.velocities, xn, x)
                                  : sim.output();
        const bool probes_finite = !frame.probes.values || read_probes(sim, frame, done);
        out[done++] = sample;
        if (!std::isfinite(sample) || !probes_finite) break;
    }
    return done;
}

// compute_hand_link_forces() for links that tick at every step, without accounts; `slower`:
// whether any slower level ticks now (when none does, no hand hands a link's sums over).
[[gnu::always_inline]] inline void Simulation::BowedChainLoop::hand_links(Simulation& sim,
                                                                          BowedChainFrame& frame,
                                                                          const double* x,
                                                                          bool slower) {
    const int* const active = sim.active_.data();
    double hand_work = 0;
    for (int i = 0; i < frame.hands; ++i) {
        HandLinkState& l = frame.hand[i];
        const double at = hand_link::hand_seen_at(l.from, l.to, sim.period_done_[l.hand_level]);
        const hand_link::Tick t = hand_link::tick(l, at, x[l.end]);
        frame.ext[l.end] += t.end_force;
        hand_work += t.work;
        if (slower && active[l.hand_level])
            hand_link::hand_over(l, l.hand_weight, *l.hand_force, *l.gesture);
    }
    sim.hand_work_ += hand_work;
}

void Simulation::BowedChainLoop::hold_hands(const Simulation& sim, BowedChainFrame& frame) {
    for (int i = 0; i < frame.hands; ++i) {
        const HandLinkPlan& p = sim.hand_plan_[i];
        const CompiledCrossLink& l = *p.link;
        frame.hand[i] = {.link = p.link,
                         .k = l.k,
                         .zdt = l.zdt,
                         .length = l.length,
                         .hand_sign = l.hand_sign,
                         .hand_weight = p.hand_weight,
                         .hand_is_a = l.hand_is_a,
                         .d_prev = l.d_prev,
                         .d_before = l.d_before,
                         .force = l.force,
                         .hand_seen = l.hand_seen,
                         .hand_force_sum = l.hand_force_sum,
                         .hand_work_sum = l.hand_work_sum,
                         .end = p.end_index,
                         .hand_index = p.hand_index,
                         .hand_level = p.hand_level_index,
                         .hand = p.hand_level,
                         .hand_force = p.hand_force,
                         .gesture = p.gesture};
    }
    read_hands(frame);
}

[[gnu::always_inline]] inline bool Simulation::BowedChainLoop::read_probes(Simulation& sim,
                                                                           BowedChainFrame& frame,
                                                                           std::size_t tick) {
    // Everything read once: the row's stores could otherwise alias all of it.
    const std::size_t count = sim.model_.probes.size();
    const CompiledProbe* const probes = sim.model_.probes.data();
    const CompiledLevel* const levels = sim.model_.levels.data();
    double* __restrict const row = frame.probes.values + tick * count;
    const CompiledBow& bow = frame.bow;
    bool finite = true;
    for (std::size_t i = 0; i < count; ++i) {
        const CompiledProbe& p = probes[i];
        double value = 0;
        switch (p.kind) {
            case ProbeKind::Position:
                value = levels[p.mat.level].x()[p.mat.index];
                break;
            case ProbeKind::Velocity: {
                const CompiledLevel& level = levels[p.mat.level];
                value = (level.x()[p.mat.index] - level.x_prev()[p.mat.index]) / level.dt;
                break;
            }
            case ProbeKind::Force:
                value = levels[p.mat.level].watched_force[p.watched];
                break;
            case ProbeKind::NormalForce:  // the loop's one bow
                value = bow.normal;
                break;
            case ProbeKind::FrictionForce:
                value = bow.friction;
                break;
            case ProbeKind::SlipVelocity:
                value = bow.slip_velocity;
                break;
            case ProbeKind::Energy:
                if (!frame.probes.energy) continue;
                sim.model_.bows[0] = frame.bow;
                release_hands(frame);
                value = sim.stored_energy();
                break;
            case ProbeKind::PowerIn:
                value = sim.power_in();
                break;
        }
        row[i] = value;
        finite = finite && std::isfinite(value);
    }
    return finite;
}

inline void Simulation::BowedChainLoop::release_hands(const BowedChainFrame& frame) {
    for (int i = 0; i < frame.hands; ++i) {
        const HandLinkState& l = frame.hand[i];
        CompiledCrossLink& link = *l.link;
        link.d_prev = l.d_prev, link.d_before = l.d_before, link.force = l.force;
        link.hand_seen = l.hand_seen, link.hand_force_sum = l.hand_force_sum;
        link.hand_work_sum = l.hand_work_sum;
    }
}

void Simulation::BowedChainLoop::plan_late_points(const Simulation& sim, BowedChainFrame& frame) {
    const CompiledLevel& audio = frame.audio;
    const std::size_t points = std::min<std::size_t>(audio.modal_points.size(), 64);
    std::uint64_t late = points == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << points) - 1;
    auto read = [&](int s) {
        const int p = audio.modal_point_of[s];
        if (p >= 0 && p < 64) late &= ~(std::uint64_t{1} << p);
    };
    read(frame.string), read(frame.bowed);
    for (int finger : audio.fingers)
        for (int s : sim.model_.fingers[finger].along) read(s);
    frame.late = late;
    const int pushed = audio.modal_point_of[frame.string];
    if (pushed < 0) return;
    std::uint64_t moved = 0;
    for (int q : audio.modal_points[pushed].moving_with)
        if (q < 64) moved |= std::uint64_t{1} << q;
    frame.push_moves_late = (late & ~moved) == 0;
}

// integrate(), solve_finger() and solve_bow() for the audio level of a bowed chain: the chain's
// rounds, W MATs a vector, then the other forces.
template <int W, bool kWithGrounds, bool kWithBody>
[[gnu::always_inline]] inline void Simulation::BowedChainLoop::audio_level(
    Simulation& sim, BowedChainFrame& frame, const double* x, const double* xp, double* xn) {
    CompiledLevel& audio = frame.audio;
    const double* const c = frame.coeff;
    double* const ext = frame.ext;
    double* const f = frame.chain_forces;
    // Without rest lengths: runs_as_bowed_chain().
    chain_rounds::chain_loop<W, false, kWithGrounds>(
        {x, xp, xn, frame.chain_k, frame.chain_zdt, frame.chain_length, c, frame.update_x,
         frame.update_xp, frame.update_rest, &audio.uniform, audio.unlinked},
        frame.mats);
    level_forces::recompute_used_chain_forces(frame.forces_used, audio, x, xp, f);
    level_forces::add_touched(frame.touched, c, ext, frame.held, xn);
    if constexpr (!kWithGrounds)
        level_forces::pull_grounds(frame.grounds, x, xp, c, frame.ground, xn);
    // move_modal_points(), the points that nothing reads before the bow's push left to after it
    // (every point ends where its modes are, whenever it follows them).
    if (kWithBody && !frame.modal_points.empty()) {
        level_forces::move_points_modes(frame.modal_points, c, ext, frame.held, xn);
        for (std::size_t p = 0; p < frame.modal_points.size(); ++p)
            if (!is_late(frame, p)) level_forces::follow_modes(frame.modal_points[p], xn);
    }
    for (int finger : audio.fingers) sim.solve_finger(audio, sim.model_.fingers[finger]);
    const int string = frame.string, bowed = frame.bowed;
    const double cs = frame.string_response, cb = frame.bow_response;
    const double friction = friction::solve_point_bow(
        frame.bow, {x[bowed], xp[bowed], xn[bowed], cb, x[string], xp[string], xn[string], cs},
        frame.dt, frame.inverse_dt, frame.divides);
    if constexpr (kWithBody) {  // a bow's mass may be a modal point
        sim.push_pair(audio, string, friction, bowed, -friction);
        if (frame.late != 0 && !(frame.push_moves_late && friction != 0.0))
            for (std::size_t p = 0; p < frame.modal_points.size(); ++p)
                if (is_late(frame, p)) level_forces::follow_modes(frame.modal_points[p], xn);
    } else {
        xn[string] += cs * friction;
        xn[bowed] += cb * -friction;
    }
    ext[string] += friction;
    ext[bowed] -= friction;
    level_forces::sum_watched(frame.watched, ext, frame.held, f, frame.watched_force);
    level_forces::clear_touched(frame.touched, ext);
}

}  // namespace archet
