#include "archet/analysis/string_partials.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "archet/analysis/chain_update_roots.hpp"
#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/modal_analysis.hpp"
#include "archet/analysis/mode_shape.hpp"
#include "chain_pencil.hpp"

namespace archet {

namespace {

using Complex = std::complex<double>;

// To unit length, scaled by the largest entry first: the solve's result can be near overflow.
void normalise(std::vector<Complex>& v) {
    double largest = 0;
    for (const Complex& c : v) largest = std::max(largest, std::abs(c));
    for (Complex& c : v) c /= largest;
    double norm = 0;
    for (const Complex& c : v) norm += std::norm(c);
    norm = std::sqrt(norm);
    for (Complex& c : v) c /= norm;
}

}  // namespace

std::vector<Complex> chain_mode_shape(const LinearSystem& sys, Complex z, int passes) {
    const int n = sys.size();
    if (n == 0) return {};
    const ChainPencil pencil(sys);
    // The root is exact to rounding, so the matrix is singular to rounding: a few solves from an
    // even start (two, unless a close root asks for more) leave the null vector alone.
    std::vector<Complex> shape(n, 1.0);
    for (int pass = 0; pass < passes; ++pass) {
        shape = pencil.solve(z, shape);
        normalise(shape);
    }
    return shape;
}

namespace {

std::vector<double> partials_of_the_whole_analysis(const LinearSystem& sys, const Model& model) {
    std::vector<double> partials;
    for (const ModeInfo& mode : analyse_modes_densely(sys, model).modes)
        if (!mode.support) partials.push_back(mode.frequency);
    return partials;
}

}  // namespace

std::vector<double> string_partial_frequencies(const LinearSystem& sys, const Model& model) {
    if (!sys.fingers.empty() || !is_tridiagonal(sys))
        return partials_of_the_whole_analysis(sys, model);
    check_analysable(sys);
    const double dt = sys.dt;
    std::optional<std::vector<Complex>> roots = chain_update_roots(sys);
    if (!roots) {
        // The dense solve of every root, analyse_modes()' roots to the bit (without
        // eigenvectors Eigen runs the same reduction and QR steps and only leaves out their
        // basis).
        const UpdateRoots dense = update_roots(sys);
        if (!dense.converged) refuse_unconverged_analysis();
        roots.emplace();
        for (const Complex& root : dense.roots)
            if (root.imag() > 0.0) roots->push_back(root);  // one of each pair, no real roots
    }
    // The shapes come from a solve of their own, so a mode whose energy is split within
    // rounding of half and half could be classed otherwise than analyse_modes() classes it; no
    // string has one.
    const std::vector<bool> is_support = support_dofs(sys, model);
    std::vector<std::pair<double, bool>> modes;  // frequency, support
    for (const Complex& root : *roots) {
        const EnergySplit energy = energy_split(sys, is_support, chain_mode_shape(sys, root));
        if (!energy.finite())  // a shape lost to overflow
            return partials_of_the_whole_analysis(sys, model);
        modes.emplace_back(root_frequency(root, dt), energy.support());
    }
    std::sort(modes.begin(), modes.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<double> partials;
    for (const auto& [frequency, support] : modes)
        if (!support) partials.push_back(frequency);
    return partials;
}

}  // namespace archet
