// The sums and the moves over a modal point whose modes lie in one run of storage
// (modal_point_position.hpp), built like the chain loop for AVX-512, AVX2 and plain x86-64:
// partial sum i is lane i mod W of vector i / W, so every build adds each term where the
// scalar order does and gives the same bits.

#include <immintrin.h>

#include <cstddef>
#include <stdexcept>

#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/modal_point_position.hpp"
#include "double_vectors.hpp"

namespace archet {

namespace {

using namespace double_vectors;

// The partial sums' whole rounds of eight terms.
template <int W>
[[gnu::always_inline]] inline std::size_t add_rounds(Doubles<W> (&partial)[kModalSumLanes / W],
                                                     const double* weight, std::size_t n,
                                                     const double* x) {
    using V = Doubles<W>;
    std::size_t k = 0;
    for (; k + kModalSumLanes <= n; k += kModalSumLanes)
        for (std::size_t v = 0; v < kModalSumLanes / W; ++v)
            partial[v] += load<V>(weight + k + v * W) * load<V>(x + k + v * W);
    return k;
}

// The plain build: the last terms and the tree lane by lane.
double sum_plain(const double* weight, std::size_t n, const double* x) {
    Doubles2 partial[kModalSumLanes / 2] = {};
    const std::size_t k = add_rounds<2>(partial, weight, n, x);
    double lane[kModalSumLanes];
    for (std::size_t i = 0; i < kModalSumLanes; ++i) lane[i] = partial[i / 2][i % 2];
    for (std::size_t i = 0; k + i < n; ++i) lane[i] += weight[k + i] * x[k + i];
    return add_partial_sums(lane);
}

// AVX-512 and AVX2: the last terms (fewer than eight, into the first partial sums) read by
// masked loads, which neither read nor fault past the run, and the tree in the registers: the
// lanes it keeps add the scalar tree's operands in its order.
ARCHET_TARGET_AVX512 double sum_avx512(const double* weight, std::size_t n, const double* x) {
    Doubles8 partial[1] = {};
    const std::size_t k = add_rounds<8>(partial, weight, n, x);
    if (k < n) {
        const __mmask8 last = static_cast<__mmask8>((1u << (n - k)) - 1u);
        partial[0] = _mm512_mask_add_pd(
            partial[0], last, partial[0],
            _mm512_maskz_loadu_pd(last, weight + k) * _mm512_maskz_loadu_pd(last, x + k));
    }
    const Doubles8 p = partial[0];
    const Doubles8 pairs = p + __builtin_shufflevector(p, p, 1, 0, 3, 2, 5, 4, 7, 6);
    const Doubles8 quads = pairs + __builtin_shufflevector(pairs, pairs, 2, 3, 0, 1, 6, 7, 4, 5);
    return quads[0] + quads[4];
}

__attribute__((target("avx2"))) double sum_avx2(const double* weight, std::size_t n,
                                                const double* x) {
    Doubles4 partial[2] = {};
    const std::size_t k = add_rounds<4>(partial, weight, n, x);
    for (std::size_t v = 0; v < 2 && k + v * 4 < n; ++v) {
        const long long left = static_cast<long long>(n - k - v * 4);
        const __m256i lanes =
            _mm256_set_epi64x(left > 3 ? -1 : 0, left > 2 ? -1 : 0, left > 1 ? -1 : 0, -1);
        const Doubles4 term = _mm256_maskload_pd(weight + k + v * 4, lanes) *
                              _mm256_maskload_pd(x + k + v * 4, lanes);
        partial[v] = _mm256_blendv_pd(partial[v], partial[v] + term, _mm256_castsi256_pd(lanes));
    }
    Doubles4 quad[2];
    for (int v = 0; v < 2; ++v) {
        const Doubles4 pairs =
            partial[v] + __builtin_shufflevector(partial[v], partial[v], 1, 0, 3, 2);
        quad[v] = pairs + __builtin_shufflevector(pairs, pairs, 2, 3, 0, 1);
    }
    return quad[0][0] + quad[1][0];
}

template <int W>
[[gnu::always_inline]] inline void run_move(const double* weight, std::size_t n,
                                            const double* coeff, double* xn, double force) {
    using V = Doubles<W>;
    const V f = broadcast<V>(force);
    std::size_t k = 0;
    for (; k + W <= n; k += W)
        store(xn + k, load<V>(xn + k) + load<V>(coeff + k) * load<V>(weight + k) * f);
    for (; k < n; ++k) xn[k] += coeff[k] * weight[k] * force;
}

using RunSum = double (*)(const double*, std::size_t, const double*);
using RunMove = void (*)(const double*, std::size_t, const double*, double*, double);

ARCHET_TARGET_AVX512 void move_avx512(const double* w, std::size_t n, const double* c, double* xn,
                                      double f) {
    run_move<8>(w, n, c, xn, f);
}
__attribute__((target("avx2"))) void move_avx2(const double* w, std::size_t n, const double* c,
                                               double* xn, double f) {
    run_move<4>(w, n, c, xn, f);
}
void move_plain(const double* w, std::size_t n, const double* c, double* xn, double f) {
    run_move<2>(w, n, c, xn, f);
}

// The builds, indexed by ChainBuild: the chain loop's choice, read at each call rather than
// copied into a global of this file, which could be initialised before the choice is made.
struct Build {
    RunSum sum;
    RunMove move;
};
constexpr Build kBuilds[] = {
    {sum_plain, move_plain}, {sum_avx2, move_avx2}, {sum_avx512, move_avx512}};

const Build& build_here(ChainBuild build) {
    if (!chain_build_runs_here(build)) throw std::logic_error("modal build not run here");
    return kBuilds[static_cast<int>(build)];
}

}  // namespace

double modal_run_sum(const double* weight, std::size_t n, const double* x) {
    return kBuilds[static_cast<int>(chosen_chain_build())].sum(weight, n, x);
}

double modal_run_sum(const double* weight, std::size_t n, const double* x, ChainBuild build) {
    return build_here(build).sum(weight, n, x);
}

void modal_run_move(const double* weight, std::size_t n, const double* coeff, double* xn,
                    double force) {
    kBuilds[static_cast<int>(chosen_chain_build())].move(weight, n, coeff, xn, force);
}

void modal_run_move(const double* weight, std::size_t n, const double* coeff, double* xn,
                    double force, ChainBuild build) {
    build_here(build).move(weight, n, coeff, xn, force);
}

}  // namespace archet
