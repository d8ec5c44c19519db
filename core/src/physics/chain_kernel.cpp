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

#include "chain_rounds.hpp"
#include "double_vectors.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace archet {

namespace {

using namespace double_vectors;
using namespace chain_rounds;

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
                             &lv.uniform,
                             lv.unlinked};
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
