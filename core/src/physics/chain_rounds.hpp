#pragma once
// The chain loop's rounds, written once over vectors of W doubles (chain_kernel.cpp builds
// them for each instruction set, the bowed chain's loop inlines them into its own builds).
// Private to the physics sources.

#include <span>

#include "archet/physics/compiled_model.hpp"
#include "double_vectors.hpp"

namespace archet::chain_rounds {

using namespace double_vectors;

// {a[W−1], b[0], …, b[W−2]}: the lanes of b moved up one, a's last lane entering.
[[gnu::always_inline]] inline Doubles8 shift_in(Doubles8 a, Doubles8 b) {
    return __builtin_shufflevector(a, b, 7, 8, 9, 10, 11, 12, 13, 14);
}
[[gnu::always_inline]] inline Doubles4 shift_in(Doubles4 a, Doubles4 b) {
    return __builtin_shufflevector(a, b, 3, 4, 5, 6);
}
[[gnu::always_inline]] inline Doubles2 shift_in(Doubles2 a, Doubles2 b) {
    return __builtin_shufflevector(a, b, 1, 2);
}

// {a[1], …, a[W−1], b[0]}: a's lanes moved down one, b's first lane entering.
[[gnu::always_inline]] inline Doubles8 next_of(Doubles8 a, Doubles8 b) {
    return __builtin_shufflevector(a, b, 1, 2, 3, 4, 5, 6, 7, 8);
}
[[gnu::always_inline]] inline Doubles4 next_of(Doubles4 a, Doubles4 b) {
    return __builtin_shufflevector(a, b, 1, 2, 3, 4);
}
[[gnu::always_inline]] inline Doubles2 next_of(Doubles2 a, Doubles2 b) {
    return __builtin_shufflevector(a, b, 1, 2);
}

struct ChainArrays {
    const double *x, *xp;          ///< x[n], x[n−1]
    double* xn;                    ///< x[n+1]
    const double *k, *z, *length;  ///< chain link j joins storage j and j + 1
    const double* c;               ///< T²/m
    const double *a, *b, *e;       ///< the grounds folded into the update (fold_ground())
    const UniformRuns* uniform;    ///< MATs whose coefficients are broadcast rather than read
    std::span<const UnlinkedRun> unlinked;  ///< MATs moved by their own update alone
};

// A MAT's new position from its two chain links, and its ground where the loop takes them.
template <bool kWithGrounds, class T>
[[gnu::always_inline]] inline T mat_update(T x, T xp, T c, T left, T right, T a, T b, T e) {
    if constexpr (kWithGrounds)
        return grounded_update(x, xp, a, b, e, c, left, right);
    else
        return chain_update(x, xp, c, left, right);
}

// The rounds of the chain loop, W MATs each, carrying from one round to the next the force of
// the link on the left of its first MAT and the positions it has already read.
template <int W, bool kWithLength, bool kWithGrounds>
class ChainRounds {
    using V = Doubles<W>;

  public:
    [[gnu::always_inline]] explicit ChainRounds(const ChainArrays& arrays)
        : x_(arrays.x),
          xp_(arrays.xp),
          xn_(arrays.xn),
          k_(arrays.k),
          z_(arrays.z),
          length_(arrays.length),
          c_(arrays.c),
          a_(arrays.a),
          b_(arrays.b),
          e_(arrays.e) {
        enter(1);
    }

    /// The rounds that start at storage `begin` (1 + a multiple of W) and before `end`,
    /// reading each MAT's coefficients from the arrays.
    [[gnu::always_inline]] void run(int begin, int end) { rounds<false>(begin, end, Shared{}); }

    /// The same over MATs whose coefficients are all `shared`: broadcast, not read.
    [[gnu::always_inline]] void run_shared(int begin, int end, const ChainLanes& shared) {
        rounds<true>(
            begin, end,
            Shared{load<V>(shared.k), load<V>(shared.zdt), load<V>(shared.length),
                   load<V>(shared.c), load<V>(shared.a), load<V>(shared.b), load<V>(shared.e)});
    }

    /// The same over MATs of an unlinked run that moves alone: each by its own update, which
    /// is the chain's to the bit (unlinked_runs.hpp says why).
    [[gnu::always_inline]] void run_unlinked(int begin, int end) {
        static_assert(kWithGrounds, "a MAT's own update without a ground may be -0");
        for (int s = begin; s < end; s += W)
            store(xn_ + s,
                  (load<V>(a_ + s) * load<V>(x_ + s) + load<V>(b_ + s) * load<V>(xp_ + s)) +
                      load<V>(e_ + s));
        enter(end);
    }

  private:
    // The round from storage s on carries the force of the link on its left in the last lane
    // of the forces before it (link 0, for MAT 1's), and the positions it reads first.
    [[gnu::always_inline]] void enter(int s) {
        forces_[W - 1] = link_force<kWithLength>(x_[s - 1] - x_[s], xp_[s - 1] - xp_[s], k_[s - 1],
                                                 z_[s - 1], kWithLength ? length_[s - 1] : 0.0);
        xs_ = load<V>(x_ + s), xps_ = load<V>(xp_ + s);
    }

    // x[s + 1 … s + W]. On AVX-512, shifted in from the vector after: one shuffle, where a
    // 64-byte load one MAT off would straddle two cache lines every time. On the narrower
    // builds, loaded again, every other load straddling two lines on AVX2: its shift takes two
    // shuffles (its lanes are two halves), and on AMD Zen 3, where this was measured, the loop
    // waited for them rather than for loads (loading took a fifth to a quarter off); for SSE2's
    // one shuffle a micro-benchmark there found the load no slower. The loop never writes x
    // or x⁻, so the load waits for no store.
    [[gnu::always_inline]] V next_along(const double* __restrict array, int s, V here,
                                        V after) const {
        if constexpr (W == 8)
            return next_of(here, after);
        else
            return load<V>(array + s + 1);
    }

    struct Shared {
        V k, z, length, c, a, b, e;
    };

    template <bool kShared>
    [[gnu::always_inline]] void rounds(int begin, int end, const Shared& shared) {
        for (int s = begin; s < end; s += W) {
            const V x_after = load<V>(x_ + s + W), xp_after = load<V>(xp_ + s + W);
            const V d = xs_ - next_along(x_, s, xs_, x_after),
                    dp = xps_ - next_along(xp_, s, xps_, xp_after);
            const V right = link_force<kWithLength>(d, dp, coefficient<kShared>(k_, s, shared.k),
                                                    coefficient<kShared>(z_, s, shared.z),
                                                    length<kShared>(s, shared.length));
            store(xn_ + s, mat_update<kWithGrounds>(
                               xs_, xps_, coefficient<kShared>(c_, s, shared.c),
                               shift_in(forces_, right), right, ground<kShared>(a_, s, shared.a),
                               ground<kShared>(b_, s, shared.b), ground<kShared>(e_, s, shared.e)));
            forces_ = right, xs_ = x_after, xps_ = xp_after;
        }
    }

    template <bool kShared>
    [[gnu::always_inline]] V coefficient(const double* __restrict array, int s, V shared) const {
        if constexpr (kShared)
            return shared;
        else
            return load<V>(array + s);
    }
    template <bool kShared>
    [[gnu::always_inline]] V length(int s, V shared) const {
        if constexpr (kWithLength)
            return coefficient<kShared>(length_, s, shared);
        else
            return V{};
    }
    template <bool kShared>
    [[gnu::always_inline]] V ground(const double* __restrict array, int s, V shared) const {
        if constexpr (kWithGrounds)
            return coefficient<kShared>(array, s, shared);
        else
            return V{};
    }

    // Restrict copies: the vector stores are byte copies, which the compiler would otherwise
    // assume may overwrite the pointers themselves, reloading them every round.
    const double* __restrict x_;
    const double* __restrict xp_;
    double* __restrict xn_;
    const double* __restrict k_, * __restrict z_, * __restrict length_, * __restrict c_;
    const double* __restrict a_, * __restrict b_, * __restrict e_;
    V forces_{}, xs_, xps_;
};

// MATs 1 … n; storage 0 and n + 1 are padding, and links 0 and n have zero coefficients.
// Whole rounds only: the last one runs up to W − 1 MATs past MAT n into the zeros kept after
// the storage, whose zero coefficients keep them zero (while the motion is finite: a blown-up
// level, which is never stepped again, may leave NaN there), and each round also reads the
// vector after its own from x and x⁻ (CompiledLevel::kReadAhead ≥ 2W − 1). The rounds that
// lie wholly inside one of the level's runs of alike MATs broadcast its coefficients, those
// wholly inside an unlinked run move their MATs by their own update (the runs of both kinds
// are disjoint and in order, so are their rounds).
template <int W, bool kWithLength, bool kWithGrounds>
[[gnu::always_inline]] inline void chain_loop(const ChainArrays& arrays, int n) {
    static_assert(CompiledLevel::kReadAhead >= 2 * W - 1);
    ChainRounds<W, kWithLength, kWithGrounds> rounds(arrays);
    int s = 1;
    // The unlinked runs that start before `limit` (only a level whose grounds the loop takes
    // has any: find_unlinked_runs()).
    std::size_t next_unlinked = 0;
    auto unlinked_before = [&](int limit) {
        if constexpr (kWithGrounds)
            for (; next_unlinked < arrays.unlinked.size() &&
                   arrays.unlinked[next_unlinked].first < limit;
                 ++next_unlinked) {
                const UnlinkedRun& run = arrays.unlinked[next_unlinked];
                const SharedRounds alone = run.rounds(W);
                if (alone.begin == alone.end || !run.moves_alone()) continue;
                rounds.run(s, alone.begin);
                rounds.run_unlinked(alone.begin, alone.end);
                s = alone.end;
            }
    };
    for (const UniformSpan& run : arrays.uniform->all()) {
        const SharedRounds shared = run.rounds(W);
        if (shared.begin == shared.end) continue;
        unlinked_before(run.first);
        rounds.run(s, shared.begin);
        rounds.run_shared(shared.begin, shared.end, run.lanes);
        s = shared.end;
    }
    unlinked_before(n + 1);
    rounds.run(s, n + 1);
}

}  // namespace archet::chain_rounds
