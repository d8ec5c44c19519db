#include "archet/builders/harmonic_chain.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace archet {

std::vector<double> prewarped_eigenvalues(const std::vector<double>& frequencies, double fs) {
    std::vector<double> lambda;
    for (double f : frequencies) {
        const double s = std::sin(std::numbers::pi * f / fs);
        lambda.push_back(4.0 * fs * fs * s * s);
    }
    return lambda;
}

ChainProfile chain_with_eigenvalues(const std::vector<double>& lambda, double total_mass) {
    const int n = static_cast<int>(lambda.size());
    if (n < 1) throw std::domain_error("no eigenvalues");
    for (int k = 0; k < n; ++k)
        if (!(lambda[k] > 0) || (k > 0 && !(lambda[k] > lambda[k - 1])))
            throw std::domain_error("eigenvalues must be positive and strictly increasing");

    // Spectral weights of a mirror-symmetric Jacobi matrix: w_k ∝ 1/∏_{j≠k}|λk − λj|, in logs.
    Eigen::VectorXd log_w(n);
    for (int k = 0; k < n; ++k) {
        double sum = 0;
        for (int j = 0; j < n; ++j)
            if (j != k) sum -= std::log(std::abs(lambda[k] - lambda[j]));
        log_w[k] = sum;
    }
    Eigen::VectorXd q = (0.5 * (log_w.array() - log_w.maxCoeff())).exp();  // √w
    q.normalize();

    // Lanczos on diag(λ) from √w, with full re-orthogonalisation, gives the Jacobi matrix.
    const Eigen::VectorXd d = Eigen::Map<const Eigen::VectorXd>(lambda.data(), n);
    Eigen::MatrixXd basis(n, n);
    Eigen::VectorXd alpha(n), beta = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) {
        basis.col(i) = q;
        Eigen::VectorXd w = d.cwiseProduct(q);
        alpha[i] = q.dot(w);
        for (int pass = 0; pass < 2; ++pass)
            w -= basis.leftCols(i + 1) * (basis.leftCols(i + 1).transpose() * w);
        if (i + 1 == n) break;
        beta[i] = w.norm();
        if (!(beta[i] > 1e-12 * d.maxCoeff())) throw std::domain_error("Lanczos broke down");
        q = w / beta[i];
    }
    Eigen::MatrixXd jacobi = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
        jacobi(i, i) = alpha[i];
        if (i + 1 < n) jacobi(i, i + 1) = jacobi(i + 1, i) = -beta[i];  // springs pull: negative
    }
    // J·x = e1 + eN: x > 0 gives the mass distribution, J·x the end springs.
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
    rhs[0] += 1, rhs[n - 1] += 1;
    const Eigen::VectorXd x = jacobi.partialPivLu().solve(rhs);
    if (!(x.minCoeff() > 0)) throw std::domain_error("no positive mass distribution");
    const double scale = total_mass / x.squaredNorm();

    ChainProfile chain;
    for (int i = 0; i < n; ++i) chain.masses.push_back(scale * x[i] * x[i]);
    const Eigen::VectorXd jx = jacobi * x;
    chain.springs.push_back(scale * x[0] * jx[0]);
    for (int i = 0; i + 1 < n; ++i) chain.springs.push_back(scale * beta[i] * x[i] * x[i + 1]);
    chain.springs.push_back(scale * x[n - 1] * jx[n - 1]);
    return chain;
}

}  // namespace archet
