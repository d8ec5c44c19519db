#pragma once
// A fixed–fixed chain with any spectrum (after Incerti 1996): an inverse eigenvalue problem
// for a mirror-symmetric Jacobi matrix, solved by Lanczos from the spectral weights that
// symmetry fixes (physics.md §2).

#include <vector>

namespace archet {

struct ChainProfile {
    std::vector<double> masses;   ///< n masses, kg
    std::vector<double> springs;  ///< n + 1 springs, N/m: ground–m1, m1–m2, …, mn–ground
};

/// The chain whose M⁻¹K has eigenvalues `lambda` (1/s², strictly increasing, positive) and
/// whose masses sum to `total_mass`. Throws std::domain_error when no such chain is found.
ChainProfile chain_with_eigenvalues(const std::vector<double>& lambda, double total_mass);

/// Eigenvalues that put the scheme's discrete frequencies exactly on `frequencies` (Hz) at
/// `sample_rate`: λ = (4/T²)·sin²(π·f·T). Each frequency must be below sample_rate / 2.
std::vector<double> prewarped_eigenvalues(const std::vector<double>& frequencies,
                                          double sample_rate);

}  // namespace archet
