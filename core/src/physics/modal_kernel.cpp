// The sums and the moves over a modal point whose modes lie in one run of storage
// (modal_point_position.hpp), built like the chain loop for AVX-512, AVX2 and plain x86-64:
// partial sum i is lane i mod W of vector i / W, so every build adds each term where the
// scalar order does and gives the same bits.

#include <cstddef>
#include <stdexcept>

#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/modal_point_position.hpp"
#include "double_vectors.hpp"

namespace archet {

namespace {

using namespace double_vectors;

template <int W>
[[gnu::always_inline]] inline double run_sum(const double* weight, std::size_t n, const double* x) {
    using V = Doubles<W>;
    constexpr std::size_t kVectors = kModalSumLanes / W;
    V partial[kVectors] = {};
    std::size_t k = 0;
    for (; k + kModalSumLanes <= n; k += kModalSumLanes)
        for (std::size_t v = 0; v < kVectors; ++v)
            partial[v] += load<V>(weight + k + v * W) * load<V>(x + k + v * W);
    double lane[kModalSumLanes];
    for (std::size_t i = 0; i < kModalSumLanes; ++i) lane[i] = partial[i / W][i % W];
    for (std::size_t i = 0; k + i < n; ++i) lane[i] += weight[k + i] * x[k + i];
    return add_partial_sums(lane);
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

ARCHET_TARGET_AVX512 double sum_avx512(const double* w, std::size_t n, const double* x) {
    return run_sum<8>(w, n, x);
}
__attribute__((target("avx2"))) double sum_avx2(const double* w, std::size_t n, const double* x) {
    return run_sum<4>(w, n, x);
}
double sum_plain(const double* w, std::size_t n, const double* x) {
    return run_sum<2>(w, n, x);
}

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
