#include "archet/builders/string_losses.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/common/input_error.hpp"
#include "archet/common/tridiagonal_solve.hpp"
#include "archet/model/linear_system.hpp"
#include "archet/model/symmetric_eigen.hpp"

namespace archet {

namespace {

constexpr double kLn1000 = 6.907755278982137;  // 60 dB of amplitude

std::string fmt(double x) {
    std::ostringstream s;
    s.precision(3);
    s << x;
    return s.str();
}

// One string mode's decay rate as a function of the two unknowns: a·σ0 + c·σ1 + rest.
struct ModeCoefficients {
    double frequency = 0.0;
    double a = 0.0;     // the string's share of the mode's inertia
    double c = 0.0;     // φᵀ·K_string·φ: ω² for a mode that lives in the string
    double rest = 0.0;  // ½·φᵀ·Z·φ of the dampers already there
};

Eigen::MatrixXd dense(const Eigen::SparseMatrix<double>& m, int n) {
    return m.size() == 0 ? Eigen::MatrixXd::Zero(n, n) : Eigen::MatrixXd(m);
}

// The undamped modes of the model's audio-rate part, normalised to φᵀMφ = 1, with the share of
// each one's inertia that is in the string.
struct UndampedModes {
    LinearSystem system;
    Eigen::VectorXd lambda;
    Eigen::MatrixXd shapes;
    Eigen::VectorXd share;
    double frequency(int mode) const {
        const double s = std::sqrt(std::max(0.0, lambda[mode])) * system.dt / 2;
        return std::asin(std::min(1.0, s)) / (std::numbers::pi * system.dt);
    }
};

UndampedModes undamped_modes(const Model& model, const StringElements& string) {
    UndampedModes u{assemble_linear_system(model, "audio"), {}, {}, {}};
    const int n = u.system.size();
    const Eigen::VectorXd scale = u.system.mass.cwiseSqrt().cwiseInverse();
    const SymmetricEigen solved = undamped_eigen(u.system, Eigen::ComputeEigenvectors);
    if (!solved.converged) throw std::runtime_error("the string's undamped modes did not converge");
    u.lambda = solved.values;
    u.shapes = scale.asDiagonal() * solved.vectors;
    Eigen::VectorXd in_string = Eigen::VectorXd::Zero(n);
    for (int d = 0; d < n; ++d)
        for (const auto& id : string.masses)
            if (u.system.dofs[d] == id) in_string[d] = u.system.mass[d];
    u.share = (u.shapes.array().square().colwise() * in_string.array()).colwise().sum();
    return u;
}

// The null vector of A − λ·I for λ just off one of A = M^(−1/2)·K·M^(−1/2)'s eigenvalues: two
// solves, on a chain each O(n) (tridiagonal_solve()), where the dense LU is O(n³). They start
// from a vector with no symmetry: a string with like bridges is mirror-symmetric, and an even
// start, all but orthogonal to its odd modes, left their shapes off by a twentieth after two
// solves (a bridge's mode then counted as the string's).
class ShiftedSolve {
  public:
    /// For A given (mass_normalised_stiffness()), tridiagonal where `chain`.
    ShiftedSolve(const Eigen::SparseMatrix<double>& a, bool chain) : chain_(chain) {
        if (!chain_) {
            dense_ = Eigen::MatrixXd(a);
            return;
        }
        const int n = static_cast<int>(a.rows());
        for (int i = 0; i < n; ++i) {
            diagonal_.push_back(a.coeff(i, i));
            if (i + 1 < n) below_.push_back(a.coeff(i + 1, i)), above_.push_back(a.coeff(i, i + 1));
        }
    }

    Eigen::VectorXd null_vector(double shift) const {
        if (!chain_) {
            const Eigen::Index n = dense_.rows();
            const Eigen::PartialPivLU<Eigen::MatrixXd> lu(dense_ -
                                                          shift * Eigen::MatrixXd::Identity(n, n));
            Eigen::VectorXd y = start(static_cast<int>(n));
            for (int pass = 0; pass < 2; ++pass) y = lu.solve(y).normalized();
            return y;
        }
        std::vector<double> shifted = diagonal_;
        for (double& d : shifted) d -= shift;
        const Eigen::VectorXd first = start(static_cast<int>(diagonal_.size()));
        std::vector<double> y(first.data(), first.data() + first.size());
        for (int pass = 0; pass < 2; ++pass) {
            y = tridiagonal_solve(shifted, below_, above_, std::move(y));
            const double norm = Eigen::Map<const Eigen::VectorXd>(y.data(), y.size()).norm();
            for (double& v : y) v /= norm;
        }
        return Eigen::Map<const Eigen::VectorXd>(y.data(), y.size());
    }

  private:
    static Eigen::VectorXd start(int n) {
        Eigen::VectorXd y(n);
        for (int i = 0; i < n; ++i) y[i] = 1.0 + 0.5 * std::sin(0.7 * i);
        return y;
    }

    bool chain_;
    std::vector<double> diagonal_, below_, above_;
    Eigen::MatrixXd dense_;
};

// The undamped modes' λ without their shapes, and each mode's share of inertia in the string
// from its shape found by inverse iteration: what undamped_modes() gives, without the O(n³) of
// the eigenvectors.
class StringShares {
  public:
    StringShares(const LinearSystem& system, const StringElements& string)
        : StringShares(system, string, mass_normalised_stiffness(system)) {}

    const UndampedModes& modes() const { return modes_; }

    /// Σ m·φ² over the string's masses, φ = M^(−1/2)·y the mode's shape, |y| = 1: NaN where the
    /// solve failed. Shifted off λ by far less than any gap between modes, so that the solve
    /// stays finite; two solves leave the mode's shape (a close pair's mix, should two be that
    /// close: both a bridge's, or both the string's).
    double share(int mode) const {
        const Eigen::VectorXd y = shifted_.null_vector(modes_.lambda[mode] + 1e-12 * largest_);
        double share = 0;
        for (int d = 0; d < y.size(); ++d)
            if (in_string_[d]) share += y[d] * y[d];
        return share;
    }

  private:
    StringShares(const LinearSystem& system, const StringElements& string,
                 const Eigen::SparseMatrix<double>& a)
        : shifted_(a, is_tridiagonal(system)), in_string_(system.size(), false) {
        // Without eigenvectors Eigen runs the same reduction and QR steps: undamped_modes()' λ,
        // bit for bit.
        const SymmetricEigen solved = symmetric_eigen(a, Eigen::EigenvaluesOnly);
        if (!solved.converged)
            throw std::runtime_error("the string's undamped modes did not converge");
        modes_ = UndampedModes{system, solved.values, {}, {}};
        for (int d = 0; d < system.size(); ++d)
            for (const auto& id : string.masses)
                if (system.dofs[d] == id) in_string_[d] = true;
        if (modes_.lambda.size() > 0) largest_ = std::max(1.0, modes_.lambda.cwiseAbs().maxCoeff());
    }

    ShiftedSolve shifted_;
    UndampedModes modes_;
    std::vector<bool> in_string_;
    double largest_ = 1.0;
};

// First-order perturbation of the undamped modes (φᵀMφ = 1): a mode's rate is ½·φᵀZφ. The
// string's links' part of K is what removing their stiffness takes away.
ModeCoefficients mode_coefficients(const Model& model, const StringElements& string,
                                   double frequency) {
    const UndampedModes u = undamped_modes(model, string);
    int best = -1;
    for (int mode = 0; mode < u.system.size(); ++mode) {
        if (u.share[mode] < 0.5) continue;  // a bridge's or the body's own mode
        if (best < 0 ||
            std::abs(u.frequency(mode) - frequency) < std::abs(u.frequency(best) - frequency))
            best = mode;
    }
    if (best < 0) return {};
    Model without_links = model;
    for (const auto& id : string.links)
        if (Lia* l = without_links.find_lia(id)) l->stiffness = 0.0;
    const int n = u.system.size();
    const Eigen::MatrixXd k_string =
        dense(u.system.stiffness, n) -
        dense(assemble_linear_system(without_links, "audio").stiffness, n);
    const Eigen::VectorXd phi = u.shapes.col(best);
    return {u.frequency(best), u.share[best], phi.dot(k_string * phi),
            0.5 * phi.dot(dense(u.system.damping, n) * phi)};
}

// The scheme's dampers act on x[n] − x[n−1]: a mode damped at rate σ has |z|² = 1 − 2σT per
// step. These convert between σ and the decay rate the scheme gives.
double scheme_rate(double sigma, double dt) {
    return -0.5 * std::log(1.0 - 2.0 * sigma * dt) / dt;
}
double sigma_for_rate(double rate, double dt) {
    return (1.0 - std::exp(-2.0 * rate * dt)) / (2.0 * dt);
}

// The decay rate (1/s) of the mode nearest `frequency` as the scheme runs it: from `modes`, the
// eigenvalues of its one-step update (discrete_modes()), every damper included exactly.
double exact_rate(const std::vector<DiscreteMode>& modes, double frequency) {
    double best = 0, rate = 0;
    for (const auto& mode : modes)
        if (best == 0 || std::abs(mode.frequency - frequency) < std::abs(best - frequency))
            best = mode.frequency, rate = kLn1000 / mode.t60;
    return rate;
}

// First order is exact for modes that live in the string; next to a heavily damped body mode
// (the bridge hill) a string mode shares that mode's losses in a way it misses. Newton steps on
// the scheme's exact modes, with first order's sensitivities, close the gap.
StringLosses refined(const Model& model, const StringElements& string,
                     const std::array<ModeCoefficients, 2>& m, const std::array<double, 2>& rates,
                     StringLosses losses) {
    const double det = m[0].a * m[1].c - m[1].a * m[0].c;
    for (int step = 0; step < 4; ++step) {
        Model trial = model;
        apply_string_losses(trial, string, losses);
        const auto modes = discrete_modes(assemble_linear_system(trial, "audio"));
        const double e0 = rates[0] - exact_rate(modes, m[0].frequency);
        const double e1 = rates[1] - exact_rate(modes, m[1].frequency);
        if (std::abs(e0) < 0.005 * rates[0] && std::abs(e1) < 0.005 * rates[1]) break;
        losses.sigma0 = std::max(0.0, losses.sigma0 + (e0 * m[1].c - e1 * m[0].c) / det);
        losses.sigma1 = std::max(0.0, losses.sigma1 + (m[0].a * e1 - m[1].a * e0) / det);
    }
    return losses;
}

}  // namespace

double violin_string_t60(double frequency) {
    return kLn1000 / violin_string_decay_rate(frequency);
}

double violin_string_decay_rate(double frequency) {
    // Desvages's loss model: σ(ω) = d0 + d1·√ω + d2·ω + d3·ω³ (air viscosity, internal
    // friction, viscoelasticity), for the violin A string: radius 0.3 mm, density 2546.5
    // kg/m³ (0.72 g/m), Young's modulus 19.5 GPa, tension 57.1 N.
    constexpr double air_density = 1.225, air_viscosity = 1.619e-5;  // kg/m³, Pa·s
    constexpr double radius = 3e-4, density = 2546.5, young = 19.5e9, tension = 57.1;
    const double d0 = 2 * air_density * air_viscosity / (density * radius * radius);
    const double d1 = 2 * air_density * std::sqrt(2 * air_viscosity) / (density * radius);
    const double d2 = 1.0 / 18000.0;
    const double d3 = 0.003 * young * density * std::pow(std::numbers::pi, 2) *
                      std::pow(radius, 6) / (4 * tension * tension);
    const double w = 2 * std::numbers::pi * frequency;
    return d0 + d1 * std::sqrt(w) + d2 * w + d3 * w * w * w;
}

StringLosses solve_string_losses(const Model& model, const StringElements& string,
                                 const DecayTarget& low, const DecayTarget& high) {
    const double dt = 1.0 / model.sample_rate;
    const ModeCoefficients m1 = mode_coefficients(model, string, low.frequency);
    const ModeCoefficients m2 = mode_coefficients(model, string, high.frequency);
    if (!(m1.a > 0) || !(m2.c > m1.c))
        throw InputError(high.option, "the string has no mode near " + fmt(high.frequency) +
                                          " Hz above its mode near " + fmt(low.frequency) +
                                          " Hz; choose a frequency inside its band");
    // What the string's own dampers must add at each mode.
    auto wanted = [&](const DecayTarget& t, const ModeCoefficients& m) {
        return t.t60 > 0 ? sigma_for_rate(kLn1000 / t.t60, dt) - m.rest
                         : violin_string_decay_rate(m.frequency);
    };
    const double s1 = wanted(low, m1), s2 = wanted(high, m2);
    auto t60 = [&](const ModeCoefficients& m, double sigma) {
        return kLn1000 / scheme_rate(sigma + m.rest, dt);
    };
    if (!(s1 > 0))
        throw InputError(low.option, "the bridges and body alone decay the mode at " +
                                         fmt(m1.frequency) + " Hz in " + fmt(t60(m1, 0.0)) +
                                         " s; ask for less than that");
    const double det = m1.a * m2.c - m2.a * m1.c;
    const StringLosses losses{(s1 * m2.c - s2 * m1.c) / det, (m1.a * s2 - m2.a * s1) / det};
    const std::string with = " s at " + fmt(high.frequency) + " Hz with " + fmt(t60(m1, s1)) +
                             " s at " + fmt(low.frequency) + " Hz";
    if (losses.sigma1 < 0)  // the high mode would need to decay slower than σ0 alone allows
        throw InputError(high.option, "must be at most " + fmt(t60(m2, m2.a * s1 / m1.a)) + with);
    if (losses.sigma0 < 0)  // faster than link damping alone gives from the low decay
        throw InputError(high.option, "must be at least " + fmt(t60(m2, m2.c * s1 / m1.c)) + with);
    if (!(low.t60 > 0 && high.t60 > 0)) return losses;  // the string's own, on top: first order
    return refined(model, string, {m1, m2}, {kLn1000 / low.t60, kLn1000 / high.t60}, losses);
}

void apply_string_losses(Model& model, const StringElements& string, const StringLosses& losses) {
    for (const auto& id : string.masses) {
        Mat* m = model.find_mat(id);
        if (!m || !(losses.sigma0 > 0)) continue;
        m->kind = MatKind::Oscillator;  // a damper to its rest point, no spring
        m->stiffness = 0.0;
        m->damping = 2.0 * losses.sigma0 * m->mass;
    }
    for (const auto& id : string.links) {
        Lia* l = model.find_lia(id);
        if (!l) continue;
        l->damping = 2.0 * losses.sigma1 * l->stiffness;
        l->kind = l->damping > 0 ? LiaKind::SpringDamper : LiaKind::Spring;
    }
}

std::vector<double> string_mode_frequencies(const Model& model, const StringElements& string) {
    std::vector<double> f;
    const LinearSystem system = assemble_linear_system(model, "audio");
    // On a chain each shape's solve is O(n): cheaper than all the eigenvectors.
    if (is_tridiagonal(system)) {
        const StringShares shares(system, string);
        bool finite = true;
        for (int mode = 0; finite && mode < system.size(); ++mode) {
            const double share = shares.share(mode);
            finite = std::isfinite(share);
            if (share >= 0.5) f.push_back(shares.modes().frequency(mode));
        }
        if (finite) return f;  // the solver sorts λ ascending
        f.clear();
    }
    const UndampedModes u = undamped_modes(model, string);
    for (int mode = 0; mode < u.system.size(); ++mode)
        if (u.share[mode] >= 0.5) f.push_back(u.frequency(mode));
    return f;
}

double string_mode_frequency(const Model& model, const StringElements& string, double frequency) {
    const LinearSystem system = assemble_linear_system(model, "audio");
    const int n = system.size();
    if (n == 0) return 0.0;  // no mode at all
    const StringShares shares(system, string);
    const UndampedModes& u = shares.modes();
    // The modes by distance from `frequency`, the lower first among equals (as
    // mode_coefficients() picks): the first that lives in the string is the one it picks.
    std::vector<int> nearest(n);
    for (int mode = 0; mode < n; ++mode) nearest[mode] = mode;
    std::stable_sort(nearest.begin(), nearest.end(), [&](int x, int y) {
        return std::abs(u.frequency(x) - frequency) < std::abs(u.frequency(y) - frequency);
    });
    for (int mode : nearest) {
        const double share = shares.share(mode);
        if (!std::isfinite(share)) return string_mode_decay(model, string, frequency).frequency;
        if (share >= 0.5) return u.frequency(mode);
    }
    return 0.0;
}

ModeDecay exact_string_mode_decay(const Model& model, const StringElements& string,
                                  double frequency, const std::vector<DiscreteMode>& modes) {
    const double f = string_mode_frequency(model, string, frequency);
    return {f, exact_rate(modes, f)};
}

ModeDecay string_mode_decay(const Model& model, const StringElements& string, double frequency) {
    const ModeCoefficients m = mode_coefficients(model, string, frequency);
    return {m.frequency, scheme_rate(m.rest, 1.0 / model.sample_rate)};
}

}  // namespace archet
