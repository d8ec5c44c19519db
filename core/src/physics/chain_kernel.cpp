// The loops over every MAT of a level, the chain loop and the stored energy, written once over
// vectors of doubles and built for AVX-512, AVX2 and plain x86-64; the widest build the CPU
// runs is chosen once, at load time.
// Each lane does what the scalar scheme does, in the same order and without FMA contraction,
// so every build gives the same bits (the golden renders check it). Over a run of MATs that
// share their coefficients (uniform_span.hpp) it broadcasts them instead of reading them.
//
// Why vectors by hand: each MAT needs the force of the link on its left, which is the force
// the MAT before it computed on its right. Reading it back from memory makes a load straddle
// two stores still in flight, and computing it twice costs a third of the loop; a shift
// across lanes hands it over in a register. On AVX-512 the same shift gives x[s + 1] from the
// vector already loaded; the narrower builds load it (see next_along()).

#include "archet/physics/chain_kernel.hpp"

#include "double_vectors.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace archet {

namespace {

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
    explicit ChainRounds(const ChainArrays& arrays)
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
        // Link 0, on the left of MAT 1, enters as the last lane of the round before the first.
        forces_[W - 1] = link_force<kWithLength>(x_[0] - x_[1], xp_[0] - xp_[1], k_[0], z_[0],
                                                 kWithLength ? length_[0] : 0.0);
        xs_ = load<V>(x_ + 1), xps_ = load<V>(xp_ + 1);
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

  private:
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
// lie wholly inside one of the level's runs of alike MATs broadcast its coefficients (the
// runs are disjoint and in order, so are their rounds).
template <int W, bool kWithLength, bool kWithGrounds>
[[gnu::always_inline]] inline void chain_loop(const ChainArrays& arrays, int n) {
    static_assert(CompiledLevel::kReadAhead >= 2 * W - 1);
    ChainRounds<W, kWithLength, kWithGrounds> rounds(arrays);
    int s = 1;
    for (const UniformSpan& run : arrays.uniform->all()) {
        const SharedRounds shared = run.rounds(W);
        if (shared.begin == shared.end) continue;
        rounds.run(s, shared.begin);
        rounds.run_shared(shared.begin, shared.end, run.lanes);
        s = shared.end;
    }
    rounds.run(s, n + 1);
}

template <int W>
[[gnu::always_inline]] inline void chain_variant(const ChainArrays& a, int n, bool lengths,
                                                 bool grounds) {
    if (lengths)
        grounds ? chain_loop<W, true, true>(a, n) : chain_loop<W, true, false>(a, n);
    else
        grounds ? chain_loop<W, false, true>(a, n) : chain_loop<W, false, false>(a, n);
}

// What MAT s of a level stores, with its chain link to s + 1 and its ground: kinetic
// ½m((x[n]−x[n−1])/T)², ½K·d[n]·d[n−1] − (Z/4T)·(d[n]−d[n−1])² for the link, and the same
// for the spring and damper to ground. Padding and absent elements have zero coefficients.
// The kinetic term multiplies by 1/T² rather than dividing by T: a vector division costs
// as much as the rest of the sum.
template <class T>
[[gnu::always_inline]] inline T mat_energy(const CompiledLevel& lv, const double* x,
                                           const double* xp, double inverse_dt_squared, int s) {
    const T xs = load<T>(x + s), xps = load<T>(xp + s);
    const T d = xs - load<T>(x + s + 1), dp = xps - load<T>(xp + s + 1);
    const T length = load<T>(lv.chain_length.data() + s);
    const T u = d - dp;
    const T rest = load<T>(lv.ground_rest.data() + s), g = xs - xps;
    return 0.5 * load<T>(lv.mass.data() + s) * (g * g) * inverse_dt_squared +
           (0.5 * load<T>(lv.chain_k.data() + s) * (d - length) * (dp - length) -
            0.25 * load<T>(lv.chain_zdt.data() + s) * u * u) +
           (0.5 * load<T>(lv.ground_k.data() + s) * (xs - rest) * (xps - rest) -
            0.25 * load<T>(lv.ground_zdt.data() + s) * g * g);
}

// mat_energy over MATs that share their coefficients `c`, read once, leaving out the terms a
// zero coefficient makes ±0 (a zero rest length, no spring or no damper to ground). The same
// bits while the motion is finite: each product keeps its order (½m, ½K, ¼Z first), and a ±0
// term added to the rest, which is never −0 since the kinetic energy is not, changes nothing.
template <bool kLength, bool kGroundSpring, bool kGroundDamper>
[[gnu::always_inline]] inline Doubles8 shared_mat_energy(const double* x, const double* xp,
                                                         const ChainCoefficients& c,
                                                         double inverse_dt_squared, int s) {
    using V = Doubles8;
    const V xs = load<V>(x + s), xps = load<V>(xp + s);
    const V d = xs - load<V>(x + s + 1), dp = xps - load<V>(xp + s + 1);
    const V u = d - dp, g = xs - xps;
    const V length = broadcast<V>(c.length);
    const V link = kLength ? broadcast<V>(0.5 * c.k) * (d - length) * (dp - length)
                           : broadcast<V>(0.5 * c.k) * d * dp;
    V e = broadcast<V>(0.5 * c.mass) * (g * g) * inverse_dt_squared +
          (link - broadcast<V>(0.25 * c.zdt) * u * u);
    const V rest = broadcast<V>(c.rest);
    const V spring = broadcast<V>(0.5 * c.ground_k) * (xs - rest) * (xps - rest);
    const V damper = broadcast<V>(0.25 * c.ground_zdt) * g * g;
    if constexpr (kGroundSpring && kGroundDamper)
        e = e + (spring - damper);
    else if constexpr (kGroundSpring)
        e = e + spring;
    else if constexpr (kGroundDamper)
        e = e - damper;
    return e;
}

template <bool kLength, bool kGroundSpring, bool kGroundDamper>
[[gnu::always_inline]] inline void add_shared_rounds(Doubles8& sums, const double* x,
                                                     const double* xp, const ChainCoefficients& c,
                                                     double inverse_dt_squared, SharedRounds r) {
    for (int s = r.begin; s < r.end; s += 8)
        sums += shared_mat_energy<kLength, kGroundSpring, kGroundDamper>(x, xp, c,
                                                                         inverse_dt_squared, s);
}

inline bool is_plus_zero(double v) {
    return std::bit_cast<std::uint64_t>(v) == 0;
}

// Each combination of the terms in a loop of its own, as for the chain loop's variants.
template <bool kLength, bool kGroundSpring>
[[gnu::always_inline]] inline void add_shared_energy(Doubles8& sums, const double* x,
                                                     const double* xp, const ChainCoefficients& c,
                                                     double inverse_dt_squared, SharedRounds r) {
    if (is_plus_zero(c.ground_zdt))
        add_shared_rounds<kLength, kGroundSpring, false>(sums, x, xp, c, inverse_dt_squared, r);
    else
        add_shared_rounds<kLength, kGroundSpring, true>(sums, x, xp, c, inverse_dt_squared, r);
}

template <bool kLength>
[[gnu::always_inline]] inline void add_shared_energy(Doubles8& sums, const double* x,
                                                     const double* xp, const ChainCoefficients& c,
                                                     double inverse_dt_squared, SharedRounds r) {
    if (is_plus_zero(c.ground_k))
        add_shared_energy<kLength, false>(sums, x, xp, c, inverse_dt_squared, r);
    else
        add_shared_energy<kLength, true>(sums, x, xp, c, inverse_dt_squared, r);
}

// Σ mat_energy over MATs 1 … size in eight interleaved partial sums (MAT s in lane
// (s − 1) mod 8), added up in a fixed tree: the same bits on every build, and eight
// independent additions in flight instead of one chain of them. Rounds of eight wholly
// inside one of the level's runs of alike MATs read its coefficients once.
[[gnu::always_inline]] inline double level_energy(const CompiledLevel& lv) {
    const double* x = lv.x();
    const double* xp = lv.x_prev();
    const double inverse_dt_squared = 1.0 / (lv.dt * lv.dt);
    Doubles8 sums{};
    int s = 1;
    for (const UniformSpan& run : lv.uniform.all()) {
        const SharedRounds shared = run.rounds(8);
        if (shared.begin == shared.end) continue;
        for (; s < shared.begin; s += 8)
            sums += mat_energy<Doubles8>(lv, x, xp, inverse_dt_squared, s);
        if (is_plus_zero(run.shared.length))
            add_shared_energy<false>(sums, x, xp, run.shared, inverse_dt_squared, shared);
        else
            add_shared_energy<true>(sums, x, xp, run.shared, inverse_dt_squared, shared);
        s = shared.end;
    }
    for (; s + 7 <= lv.size; s += 8) sums += mat_energy<Doubles8>(lv, x, xp, inverse_dt_squared, s);
    for (int lane = 0; s <= lv.size; ++s, ++lane)
        sums[lane] += mat_energy<double>(lv, x, xp, inverse_dt_squared, s);
    return ((sums[0] + sums[1]) + (sums[2] + sums[3])) +
           ((sums[4] + sums[5]) + (sums[6] + sums[7]));
}

using ChainLoop = void (*)(const ChainArrays&, int, bool, bool);
using EnergySum = double (*)(const CompiledLevel&);

ARCHET_TARGET_AVX512 void chain_avx512(const ChainArrays& a, int n, bool lengths, bool grounds) {
    chain_variant<8>(a, n, lengths, grounds);
}

__attribute__((target("avx2"))) void chain_avx2(const ChainArrays& a, int n, bool lengths,
                                                bool grounds) {
    chain_variant<4>(a, n, lengths, grounds);
}

void chain_plain(const ChainArrays& a, int n, bool lengths, bool grounds) {
    chain_variant<2>(a, n, lengths, grounds);
}

// The energy is summed in eight lanes on every build (the plain one in pairs), so that
// each gives the same bits.
ARCHET_TARGET_AVX512 double energy_avx512(const CompiledLevel& lv) {
    return level_energy(lv);
}

__attribute__((target("avx2"))) double energy_avx2(const CompiledLevel& lv) {
    return level_energy(lv);
}

double energy_plain(const CompiledLevel& lv) {
    return level_energy(lv);
}

// The builds, indexed by ChainBuild.
struct Build {
    ChainLoop chain;
    EnergySum energy;
};
constexpr Build kBuilds[] = {
    {chain_plain, energy_plain}, {chain_avx2, energy_avx2}, {chain_avx512, energy_avx512}};

ChainBuild chosen_at_load() {
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f")) return ChainBuild::Avx512;
    if (__builtin_cpu_supports("avx2")) return ChainBuild::Avx2;
    return ChainBuild::Plain;
}

// Chosen by a plain CPU check rather than an ifunc resolver (ThreadSanitizer instruments
// resolvers, which run before it is set up), before main(): the real-time thread never
// makes the choice.
const ChainBuild chosen = chosen_at_load();
const Build& chosen_build = kBuilds[static_cast<int>(chosen)];

// A given build, for tests and benchmarks: it must run on this CPU.
const Build& build_here(ChainBuild build) {
    if (!chain_build_runs_here(build)) throw std::logic_error("chain build not run here");
    return kBuilds[static_cast<int>(build)];
}

void run_chain(ChainLoop loop, CompiledLevel& lv, double* xn) {
    const ChainArrays arrays{lv.x(),
                             lv.x_prev(),
                             xn,
                             lv.chain_k.data(),
                             lv.chain_zdt.data(),
                             lv.chain_length.data(),
                             lv.coeff.data(),
                             lv.update_x.data(),
                             lv.update_xp.data(),
                             lv.update_rest.data(),
                             &lv.uniform};
    loop(arrays, lv.size - lv.fixed_after, lv.has_chain_lengths, grounds_in_chain_loop(lv));
}

}  // namespace

ChainBuild chosen_chain_build() {
    return chosen;
}

bool chain_build_runs_here(ChainBuild build) {
    return build <= chosen;
}

const char* chain_build_name(ChainBuild build) {
    switch (build) {
        case ChainBuild::Avx512:
            return "avx512";
        case ChainBuild::Avx2:
            return "avx2";
        case ChainBuild::Plain:
            break;
    }
    return "plain";
}

void fold_ground(CompiledLevel& lv, int s) {
    const double c = lv.coeff[s], k = lv.ground_k[s], z = lv.ground_zdt[s];
    lv.update_x[s] = (2.0 - c * k) - c * z;
    lv.update_xp[s] = c * z - 1.0;
    lv.update_rest[s] = c * k * lv.ground_rest[s];
}

void fold_grounds(CompiledLevel& lv) {
    for (int s = 1; s <= lv.size; ++s) fold_ground(lv, s);
}

double level_stored_energy(const CompiledLevel& lv) {
    return chosen_build.energy(lv);
}

double level_stored_energy(const CompiledLevel& lv, ChainBuild build) {
    return build_here(build).energy(lv);
}

void integrate_chain(CompiledLevel& lv, double* xn) {
    run_chain(chosen_build.chain, lv, xn);
}

void integrate_chain(CompiledLevel& lv, double* xn, ChainBuild build) {
    run_chain(build_here(build).chain, lv, xn);
}

}  // namespace archet
