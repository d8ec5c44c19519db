#pragma once
// The floor of the peer benchmark: Archet's paper string ("archet paper") with its step
// written out by hand for that one model and its string kept in AVX-512 registers over each
// block. It does what Simulation::step() does for the sound, in the same order, so it gives
// the same bytes (bench_peers checks that before timing it), and nothing a general step needs
// besides: no lists, no levels, no books (the hand's work, the device's force). What it costs
// is what this scheme costs on this machine, whatever the engine around it.
// Besides the registers, three things make it cheaper (all measured against the plain hand-
// written step, the same bytes): each link's stretch is carried from the step before rather
// than computed again from x⁻; the lanes of the MATs the step reads alone (the bridge, the bow's
// pair, the pressure buffer, the nut) are read once, and each is written once, after all its
// forces are added; the first link's force is the chain's own lane, not computed again.
// The fused floor also fuses the chain's multiply-adds (FMA): a change of the scheme's
// arithmetic, so other bits, which it reports as its largest difference from the scheme's
// sound. (The scheme does not fuse them: a CPU without FMA would compute them in software.)
// It stands only for the paper string at 220 Hz, 60 masses, bowed at mass 7: storage
// 1 bridge, 2–61 the string, 62 nut, 63 bow, 64 bow pressure, 65 surface (fixed), and two
// hand links from a 3 kHz hand. layout_error() says what differs when the builder changes.

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include "archet/model/gesture.hpp"
#include "archet/physics/simulation.hpp"

namespace archet::peers {

namespace floor_detail {

typedef double V __attribute__((vector_size(64)));

constexpr int kRounds = 8;  // storage 1 … 64: the fixed surface (65) is left out
constexpr int kBridge = 1, kString = 8, kNut = 62, kBow = 63, kPress = 64, kSurface = 65;
constexpr int kHapticDivider = 16;

// Every helper of render() is built for AVX-512 as it is, in whole 512-bit vectors (as
// double_vectors.hpp asks each compiler).
#if defined(__clang__)
#define ARCHET_FLOOR_TARGET __attribute__((target("avx512f,fma"), min_vector_width(512)))
#else
#define ARCHET_FLOOR_TARGET __attribute__((target("avx512f,fma,prefer-vector-width=512")))
#endif

constexpr int round_of(int s) {
    return (s - 1) / 8;
}
constexpr int lane_of(int s) {
    return (s - 1) % 8;
}

}  // namespace floor_detail

/// What keeps the floor from standing for `model`, or "" when it can.
inline std::string layout_error(const Simulation& sim) {
    using namespace floor_detail;
    const CompiledModel& m = sim.model();
    if (!__builtin_cpu_supports("avx512f") || !__builtin_cpu_supports("fma"))
        return "this CPU has no AVX-512";
    if (m.levels.size() != 2 || m.levels[0].divider != 1 || m.levels[1].divider != kHapticDivider)
        return "not an audio level and a 3 kHz hand";
    const CompiledLevel& a = m.levels[0];
    const CompiledLevel& h = m.levels[1];
    if (a.size != kSurface || a.fixed_after != 1 || a.has_chain_lengths || !a.links.empty() ||
        !a.modal_points.empty() || !a.fingers.empty() || a.bows.size() != 1)
        return "the audio level is not the paper string's";
    if (a.grounds.size() != 2 || a.grounds[0].index != kBridge || a.grounds[1].index != kNut)
        return "the bridges are not at 1 and 62";
    if (a.touched != std::vector<int>{kString, kBow, kPress, kSurface} ||
        a.watched != std::vector<int>{kBridge})
        return "the forces land elsewhere";
    const CompiledBow& b = m.bows[0];
    if (b.bow != kBow || b.string != kString || b.press != kPress || b.surface != kSurface)
        return "the bow is not at mass 7";
    if (m.hand_links != 2 || m.cross_links.size() != 2 || !m.controls.empty() ||
        h.gestures.size() != 2 || !h.links.empty() || !h.bows.empty())
        return "the hand is not held by two links";
    for (int i = 0; i < 2; ++i) {
        const CompiledCrossLink& l = m.cross_links[i];
        if (!l.hand_is_a || l.end_slot.level != 0 || l.end_slot.index != (i == 0 ? kBow : kPress) ||
            l.hand_slot.level != 1)
            return "the hand links hold other masses";
    }
    if (m.outputs.size() != 1 || m.outputs[0].signal != Output::Signal::Force ||
        m.outputs[0].mat.level != 0 || m.outputs[0].mat.index != kBridge)
        return "the sound is not the bridge's force";
    return "";
}

/// The paper string's step by hand (see above); make it from a simulation whose gesture track
/// is set and that has not stepped, after layout_error() found nothing.
template <bool kFused>
class FloorString {
    using V = floor_detail::V;

  public:
    FloorString(const Simulation& sim, const Gesture* gesture) : gesture_(gesture) {
        using namespace floor_detail;
        const CompiledModel& m = sim.model();
        const CompiledLevel& a = m.levels[0];
        const CompiledLevel& h = m.levels[1];
        for (int r = 0; r < kRounds; ++r)
            for (int lane = 0; lane < 8; ++lane) {
                const int s = 1 + 8 * r + lane;
                k_[r][lane] = a.chain_k[s], z_[r][lane] = a.chain_zdt[s], c_[r][lane] = a.coeff[s];
                x_[r][lane] = a.x()[s], xp_[r][lane] = a.x_prev()[s];
            }
        k0_ = a.chain_k[0], z0_ = a.chain_zdt[0];
        for (int s : {kBridge, kNut})
            ground_[s == kBridge ? 0 : 1] = {a.coeff[s], a.ground_k[s], a.ground_zdt[s],
                                             a.ground_rest[s]};
        c_string_ = a.coeff[kString], c_bow_ = a.coeff[kBow], c_press_ = a.coeff[kPress];
        surface_ = a.x()[kSurface], surface_prev_ = a.x_prev()[kSurface];
        const CompiledBow& b = m.bows[0];
        kb_ = b.kb, zbdt_ = b.zbdt, mu_s_ = b.mu_s, mu_d_ = b.mu_d, v0_ = b.v0;
        inverse_csum_ = 1.0 / (c_bow_ + c_string_), inverse_dt_ = 1.0 / a.dt;
        for (int i = 0; i < 2; ++i) {
            const CompiledCrossLink& l = m.cross_links[i];
            const int point = l.hand;
            hand_[i] = {l.k,
                        l.zdt,
                        l.length,
                        l.d_prev,
                        h.x_prev()[l.hand_slot.index],
                        h.x()[l.hand_slot.index],
                        h.gestures[point].position_scale,
                        h.gestures[point].axis};
        }
        haptic_dt_ = h.dt, inverse_divider_ = h.inverse_divider;
        sample_rate_ = m.sample_rate;
        gain_ = m.outputs[0].gain, output_gain_ = m.output_gain;
    }

    /// The next `count` samples of the string's sound.
    ARCHET_FLOOR_TARGET __attribute__((noinline)) void render(double* out, int count) {
        using namespace floor_detail;
        V x[kRounds], xp[kRounds], xn[kRounds], d_prev[kRounds];
        for (int r = 0; r < kRounds; ++r) x[r] = x_[r], xp[r] = xp_[r];
        for (int r = 0; r < kRounds; ++r) {  // each link's stretch at the step before
            const V p_after = r + 1 < kRounds ? xp[r + 1] : V{surface_prev_};
            d_prev[r] = xp[r] - __builtin_shufflevector(xp[r], p_after, 1, 2, 3, 4, 5, 6, 7, 8);
        }
        for (int i = 0; i < count; ++i) {
            // The hand's level ticks once every 16 steps; between, its links see it along a line.
            const bool hand_ticks = countdown_ == 0;
            countdown_ = hand_ticks ? kHapticDivider - 1 : countdown_ - 1;
            const double done =
                hand_ticks ? 1.0 : (kHapticDivider - 1 - countdown_) * inverse_divider_;
            // The bow's pressure buffer, then the hand links (the order of `external`).
            const double x_press = lane<kPress>(x), x_bow = lane<kBow>(x);
            const double p = x_press - surface_, pp = lane<kPress>(xp) - surface_prev_;
            const double normal = p > 0.0 ? std::max(0.0, kb_ * p + zbdt_ * (p - pp)) : 0.0;
            double on_bow = 0.0, on_press = 0.0 - normal;
            on_bow += hand_force(hand_[0], x_bow, done);
            on_press += hand_force(hand_[1], x_press, done);
            // The chain loop, link 0 (from the padding to the bridge) entering on the left of
            // MAT 1; the bridge's force reads that link again, with link 1 (the first round's
            // first lane).
            const double x_bridge = lane<1>(x), xp_bridge = lane<1>(xp);
            const double d0 = 0.0 - x_bridge, dp0 = 0.0 - xp_bridge;
            const double f0 = k0_ * d0 + z0_ * (d0 - dp0);
            V left{};
            left[7] = f0;
            V first_forces;
            chain(x, xp, xn, d_prev, left, first_forces,
                  std::make_integer_sequence<int, kRounds>{});
            const double f1 = first_forces[0];
            // The other forces, where there are any (the surface's is a zero on a fixed MAT).
            double n_string = lane<kString>(xn) + c_string_ * (0.0 + 0.0);
            double n_bow = lane<kBow>(xn) + c_bow_ * (on_bow + 0.0);
            const double n_press = lane<kPress>(xn) + c_press_ * (on_press + 0.0);
            const double n_bridge =
                lane<kBridge>(xn) - ground_pull(ground_[0], x_bridge, xp_bridge);
            const double n_nut =
                lane<kNut>(xn) - ground_pull(ground_[1], lane<kNut>(x), lane<kNut>(xp));
            // The friction, on the prediction.
            const double f = friction(normal, x_bow, lane<kBow>(xp), n_bow, lane<kString>(x),
                                      lane<kString>(xp), n_string);
            n_string += c_string_ * f;
            n_bow += c_bow_ * -f;
            set<kString>(xn, n_string);
            set<kBow>(xn, n_bow);
            set<kPress>(xn, n_press);
            set<kBridge>(xn, n_bridge);
            set<kNut>(xn, n_nut);
            const double bridge_force = ((0.0 + 0.0) + f0) - f1;
            out[i] = output_gain_ * (0.0 + gain_ * bridge_force);
            if (hand_ticks) [[unlikely]] {  // where the hand is at the end of its next period
                const double t_next = static_cast<double>(tick_) / sample_rate_ + haptic_dt_;
                const GestureSample s = gesture_->at(t_next);
                for (Hand& hand : hand_) {
                    hand.from = hand.to;
                    hand.to = hand.scale * (hand.axis == GestureAxis::Slide ? s.slide : s.press);
                }
            }
            ++tick_;
            for (int r = 0; r < kRounds; ++r) xp[r] = x[r], x[r] = xn[r];
        }
        for (int r = 0; r < kRounds; ++r) x_[r] = x[r], xp_[r] = xp[r];
    }

  private:
    struct Hand {
        double k, zdt, length, d_prev, from, to, scale;
        GestureAxis axis;
    };
    struct Ground {
        double c, k, zdt, rest;
    };

    template <int s>
    [[gnu::always_inline]] ARCHET_FLOOR_TARGET static double lane(const V* v) {
        return v[floor_detail::round_of(s)][floor_detail::lane_of(s)];
    }
    template <int s>
    [[gnu::always_inline]] ARCHET_FLOOR_TARGET static void set(V* v, double value) {
        v[floor_detail::round_of(s)][floor_detail::lane_of(s)] = value;
    }

    [[gnu::always_inline]] ARCHET_FLOOR_TARGET static double ground_pull(const Ground& g, double x,
                                                                         double xp) {
        return g.c * (g.k * (x - g.rest) + g.zdt * (x - xp));
    }

    [[gnu::always_inline]] ARCHET_FLOOR_TARGET static double hand_force(Hand& l, double end,
                                                                        double done) {
        const double h = l.from + (l.to - l.from) * done;
        const double d = h - end;
        const double f = l.k * (d - l.length) + l.zdt * (d - l.d_prev);
        l.d_prev = d;
        return f;
    }

    template <int... r>
    [[gnu::always_inline]] ARCHET_FLOOR_TARGET void chain(const V* x, const V* xp, V* xn, V* d_prev,
                                                          V left, V& first_forces,
                                                          std::integer_sequence<int, r...>) const {
        (round<r>(x, xp, xn, d_prev, left, first_forces), ...);
    }
    // The round's links' forces carry into the next round as `left`; the first round's are
    // kept in `first_forces`.
    template <int r>
    [[gnu::always_inline]] ARCHET_FLOOR_TARGET void round(const V* x, const V* xp, V* xn, V* d_prev,
                                                          V& left, V& first_forces) const {
        // After the last round: the surface, fixed, and zeros past the storage.
        const V after = r + 1 < floor_detail::kRounds ? x[r + 1] : V{surface_};
        const V d = x[r] - __builtin_shufflevector(x[r], after, 1, 2, 3, 4, 5, 6, 7, 8);
        const V dp = d_prev[r];
        d_prev[r] = d;
        if constexpr (kFused) {
            const V right = _mm512_fmadd_pd(k_[r], d, z_[r] * (d - dp));
            const V from_left = __builtin_shufflevector(left, right, 7, 8, 9, 10, 11, 12, 13, 14);
            xn[r] = _mm512_fmadd_pd(c_[r], from_left - right, 2.0 * x[r] - xp[r]);
            left = right;
            if constexpr (r == 0) first_forces = right;
        } else {
            const V right = k_[r] * d + z_[r] * (d - dp);
            const V from_left = __builtin_shufflevector(left, right, 7, 8, 9, 10, 11, 12, 13, 14);
            xn[r] = 2.0 * x[r] - xp[r] + c_[r] * (from_left - right);
            left = right;
            if constexpr (r == 0) first_forces = right;
        }
    }

    // Simulation::solve_bow() for a point bow on two masses (bow_solve.cpp says why).
    [[gnu::always_inline]] ARCHET_FLOOR_TARGET double friction(double n, double xb, double xbp,
                                                               double xbn, double xs, double xsp,
                                                               double xsn) const {
        if (!(n > 0.0)) return 0.0;
        const double csum = c_bow_ + c_string_;
        const double u_prev = (xb - xbp) - (xs - xsp);
        const double u_free = (xbn - xb) - (xsn - xs);
        const double f_target = u_free * inverse_csum_;
        const double f_passive = (u_free + u_prev) * inverse_csum_;
        const double f_stick =
            std::clamp(f_target, std::min(0.0, f_passive), std::max(0.0, f_passive));
        if (std::abs(f_stick) <= mu_s_ * n) return f_stick;
        const double w_free = 0.5 * (u_free + u_prev);
        const double q_free = std::abs(w_free) * inverse_dt_;
        const double alpha = n * csum * (0.5 * inverse_dt_);
        const double b = v0_ + alpha * mu_d_ - q_free;
        const double cq = v0_ * (alpha * mu_s_ - q_free);
        const double root = std::sqrt(b * b - 4.0 * cq);
        const double q = b > 0.0 ? -2.0 * cq / (b + root) : 0.5 * (root - b);
        const double mu = mu_d_ + (mu_s_ - mu_d_) * v0_ / (v0_ + q);
        return std::copysign(n * mu, w_free);
    }

    V k_[floor_detail::kRounds], z_[floor_detail::kRounds], c_[floor_detail::kRounds];
    V x_[floor_detail::kRounds], xp_[floor_detail::kRounds];
    double k0_, z0_;
    Ground ground_[2];
    double c_string_, c_bow_, c_press_, surface_, surface_prev_;
    double kb_, zbdt_, mu_s_, mu_d_, v0_, inverse_csum_, inverse_dt_;
    Hand hand_[2];
    double haptic_dt_, inverse_divider_, sample_rate_, gain_, output_gain_;
    const Gesture* gesture_;
    int countdown_ = 0;
    std::uint64_t tick_ = 0;
};

}  // namespace archet::peers
