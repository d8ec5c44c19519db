#include "archet/analysis/discrete_modes.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace archet {

Eigen::MatrixXd update_matrix(const LinearSystem& sys) {
    const int n = sys.size();
    const double dt = sys.dt;
    const Eigen::MatrixXd inv_m = sys.mass.cwiseInverse().asDiagonal();  // dense: used below
    const Eigen::MatrixXd k = Eigen::MatrixXd(sys.stiffness) * (dt * dt);
    const Eigen::MatrixXd z = Eigen::MatrixXd(sys.damping) * dt;
    Eigen::MatrixXd step = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    step.topLeftCorner(n, n) = 2.0 * Eigen::MatrixXd::Identity(n, n) - inv_m * (k + z);
    step.topRightCorner(n, n) = inv_m * z - Eigen::MatrixXd::Identity(n, n);
    step.bottomLeftCorner(n, n) = Eigen::MatrixXd::Identity(n, n);
    // Each finger then corrects the new positions as the simulation does (simulation_finger.cpp):
    // F = α·u(x[n+1]) + β·u(x[n−1]) on its point u = gᵀx, which moves by T²M⁻¹g·F.
    for (const FingerTerm& finger : sys.fingers) {
        Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
        for (auto [d, w] : finger.point) g[d] += w;
        const Eigen::VectorXd moves = inv_m * g * (dt * dt);
        const double c = g.dot(moves), k = finger.stiffness, zdt = finger.damping / dt;
        const double alpha = -(k + zdt) / (2.0 + c * (k + zdt));
        const double beta = -(k - zdt) / (2.0 + c * (k + zdt));
        Eigen::RowVectorXd force = alpha * g.transpose() * step.topRows(n);
        force.tail(n) += beta * g.transpose();
        step.topRows(n) += moves * force;
    }
    return step;
}

UpdateRoots update_roots(LinearSystem system) {
    const Eigen::EigenSolver<Eigen::MatrixXd> solver(update_matrix(system), false);
    const bool converged = solver.info() == Eigen::Success;
    return {std::move(system), solver.eigenvalues(), converged};
}

std::vector<DiscreteMode> discrete_modes(const LinearSystem& sys) {
    if (sys.size() == 0) return {};
    return discrete_modes(update_roots(sys));
}

std::vector<DiscreteMode> discrete_modes(const UpdateRoots& update) {
    std::vector<DiscreteMode> modes;
    if (update.system.size() == 0) return modes;
    const double dt = update.system.dt;
    const double fs = 1.0 / dt;
    for (const auto& root : update.roots) {
        if (root.imag() <= 0.0) continue;  // one of each conjugate pair
        DiscreteMode mode;
        mode.frequency = std::arg(root) * fs / (2.0 * std::numbers::pi);
        mode.radius = std::abs(root);
        mode.t60 = root_t60(root, dt);
        modes.push_back(mode);
    }
    std::sort(modes.begin(), modes.end(),
              [](const auto& a, const auto& b) { return a.frequency < b.frequency; });
    return modes;
}

}  // namespace archet
