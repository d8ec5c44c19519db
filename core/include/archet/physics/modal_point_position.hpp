#pragma once
// Where a modal point is: the weighted sum of its modes' positions, the one sum the step makes
// again after every force on a modal body (see Simulation::update_modal_points()).
//
// A point of up to eight terms (a bridge on a few body modes, a bow spread over three masses)
// adds them in order. A longer one (a string in modal form, one term per mode) adds them in
// eight interleaved partial sums, term k in sum k mod 8, and the sums in a fixed tree: in order,
// each term waits for the one before, and sixty of them made a modal string five times as
// costly as the same string as a chain. The tree is revision 3 of the scheme's arithmetic
// (common/scheme_revision.hpp); every build gives the same bits, since each partial sum keeps
// its order.

#include <cstddef>

#include "archet/physics/chain_kernel.hpp"
#include "archet/physics/compiled_model.hpp"

namespace archet {

/// Points of more terms than this sum them in as many interleaved partial sums.
inline constexpr std::size_t kModalSumLanes = 8;

/// The eight partial sums of a long point added in the fixed tree revision 3 defines.
inline double add_partial_sums(const double (&partial)[kModalSumLanes]) {
    static_assert(kModalSumLanes == 8, "the tree below adds eight partial sums");
    return ((partial[0] + partial[1]) + (partial[2] + partial[3])) +
           ((partial[4] + partial[5]) + (partial[6] + partial[7]));
}

/// Σ weight[k]·x[k] for k < n, n > kModalSumLanes: the modes of a point that lie in one run of
/// storage from x, added as modal_point_position() adds them, in the widest build this CPU runs
/// (or in `build`, for tests: it must run here). modal_kernel.cpp.
double modal_run_sum(const double* weight, std::size_t n, const double* x);
double modal_run_sum(const double* weight, std::size_t n, const double* x, ChainBuild build);
/// xn[k] += coeff[k]·weight[k]·force for k < n, over such a run.
void modal_run_move(const double* weight, std::size_t n, const double* coeff, double* xn,
                    double force);
void modal_run_move(const double* weight, std::size_t n, const double* coeff, double* xn,
                    double force, ChainBuild build);

namespace modal_detail {

// The sums and the moves of the points of up to eight terms, or whose modes lie apart (`mode`
// gives mode k's storage index), inline: the first take a few operations, the second read
// their modes one by one.

// Two lanes in one SSE2 register: the compiler, left to vectorise the eight partial sums of a
// point whose modes lie apart, shuffles and spills them.
typedef double Pair __attribute__((vector_size(16)));

template <class Mode>
inline double sum(const double* weight, std::size_t n, Mode mode, const double* x) {
    static_assert(kModalSumLanes == 8, "the partial sums below are paired for 8");
    if (n <= kModalSumLanes) {
        double total = 0;
        for (std::size_t k = 0; k < n; ++k) total += weight[k] * x[mode(k)];
        return total;
    }
    Pair lanes[kModalSumLanes / 2] = {};  // partial sums 0 and 1, 2 and 3, …
    std::size_t k = 0;
    for (; k + kModalSumLanes <= n; k += kModalSumLanes)
        for (std::size_t j = 0; j < kModalSumLanes / 2; ++j)
            lanes[j] += Pair{weight[k + 2 * j], weight[k + 2 * j + 1]} *
                        Pair{x[mode(k + 2 * j)], x[mode(k + 2 * j + 1)]};
    double partial[kModalSumLanes];
    for (std::size_t i = 0; i < kModalSumLanes; ++i) partial[i] = lanes[i / 2][i % 2];
    for (std::size_t i = 0; k + i < n; ++i) partial[i] += weight[k + i] * x[mode(k + i)];
    return add_partial_sums(partial);
}

template <class Mode>
inline void move(const double* weight, std::size_t n, Mode mode, const double* coeff, double* xn,
                 double force) {
    for (std::size_t k = 0; k < n; ++k) xn[mode(k)] += coeff[mode(k)] * weight[k] * force;
}

}  // namespace modal_detail

/// Σ weight·x(mode) over the point's modes, x indexed by storage.
inline double modal_point_position(const CompiledModalPoint& point, const double* x) {
    const std::size_t n = point.modes.size();
    const double* weight = point.weights.data();
    if (point.first_mode >= 0) {
        const double* run = x + point.first_mode;
        if (n > kModalSumLanes) return modal_run_sum(weight, n, run);
        return modal_detail::sum(
            weight, n, [](std::size_t k) { return k; }, run);
    }
    const int* mode = point.modes.data();
    return modal_detail::sum(
        weight, n, [mode](std::size_t k) { return mode[k]; }, x);
}

/// Moves each of the point's modes by what `force` on the point does to it over a step,
/// T²/m·weight·force (`coeff` is the level's T²/m).
inline void add_modal_force(const CompiledModalPoint& point, const double* coeff, double* xn,
                            double force) {
    const std::size_t n = point.modes.size();
    const double* weight = point.weights.data();
    if (point.first_mode >= 0) {
        const std::size_t first = static_cast<std::size_t>(point.first_mode);
        if (n > kModalSumLanes)
            modal_run_move(weight, n, coeff + first, xn + first, force);
        else
            modal_detail::move(
                weight, n, [](std::size_t k) { return k; }, coeff + first, xn + first, force);
        return;
    }
    const int* mode = point.modes.data();
    modal_detail::move(
        weight, n, [mode](std::size_t k) { return mode[k]; }, coeff, xn, force);
}

}  // namespace archet
