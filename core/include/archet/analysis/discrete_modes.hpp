#pragma once
// Modes of a linear system exactly as the explicit scheme runs them: the eigenvalues z of
// the one-step update x[n+1] = A·x[n] + B·x[n−1] give frequency arg(z)·fs/2π and decay |z|.

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <vector>

#include "archet/model/linear_system.hpp"

namespace archet {

struct DiscreteMode {
    double frequency = 0.0;  ///< Hz
    double t60 = 0.0;        ///< s to decay by 60 dB (infinite when undamped)
    double radius = 0.0;     ///< |z| per step
};

/// A root's frequency in Hz, written once for every analysis that must give the same bits
/// (analyse_modes(), string_first_mode(), string_partial_frequencies()).
inline double root_frequency(std::complex<double> z, double dt) {
    return std::arg(z) / (2.0 * std::numbers::pi * dt);
}

/// A root's decay by 60 dB in s, infinite where it does not decay.
inline double root_t60(std::complex<double> z, double dt) {
    const double radius = std::abs(z);
    return radius < 1.0 ? std::log(1e-3) / std::log(radius) * dt
                        : std::numeric_limits<double>::infinity();
}

/// The one-step update [x[n+1]; x[n]] = U·[x[n]; x[n−1]] of the scheme for the system: with
/// the damper force from x[n] − x[n−1], x[n+1] = (2I − M⁻¹(K·T² + Z·T))·x[n] + (M⁻¹Z·T − I)·x[n−1],
/// then corrected by each finger's implicit solve.
Eigen::MatrixXd update_matrix(const LinearSystem& system);

/// The roots of a system's one-step update, the eigenvalues of update_matrix() solved without
/// eigenvectors: the costly part of an analysis (seconds for a long string), kept with the
/// system they belong to, so that the analyses of the same system share them.
struct UpdateRoots {
    LinearSystem system;
    Eigen::VectorXcd roots;  ///< all of them: each conjugate pair and the real roots
    bool converged = false;  ///< Eigen's QR iteration converged (else `roots` are not its roots)
};
UpdateRoots update_roots(LinearSystem system);

/// Oscillating modes sorted by frequency (real, non-oscillating roots are left out).
std::vector<DiscreteMode> discrete_modes(const LinearSystem& system);
std::vector<DiscreteMode> discrete_modes(const UpdateRoots& roots);

}  // namespace archet
