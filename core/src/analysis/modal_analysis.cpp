#include "archet/analysis/modal_analysis.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <set>

#include "archet/analysis/discrete_modes.hpp"
#include "archet/analysis/mode_shape.hpp"
#include "archet/common/input_error.hpp"
#include "archet/common/number_text.hpp"
#include "archet/model/finger_contact.hpp"
#include "archet/model/string_points.hpp"

namespace archet {

double ModalAnalysis::shape_at(const ModeInfo& mode, const std::string& id) const {
    const auto it = std::find(dofs.begin(), dofs.end(), id);
    if (it != dofs.end()) return mode.shape[it - dofs.begin()];
    const auto point = points.find(id);
    if (point == points.end()) return 0.0;
    double x = 0;
    for (auto [dof, weight] : point->second) x += weight * mode.shape[dof];
    return x;
}

bool ModalAnalysis::has_shape_at(const std::string& id) const {
    return points.count(id) || std::find(dofs.begin(), dofs.end(), id) != dofs.end();
}

namespace {

// What each modal point reads: (DOF, weight) pairs.
std::map<std::string, std::vector<std::pair<int, double>>> modal_point_reads(
    const LinearSystem& sys, const Model& model) {
    std::map<std::string, std::vector<std::pair<int, double>>> points;
    for (const auto& m : model.mats) {
        if (m.kind != MatKind::ModalPoint) continue;
        std::vector<std::pair<int, double>> reads;
        for (std::size_t k = 0; k < m.modes.size() && k < m.weights.size(); ++k) {
            const auto it = std::find(sys.dofs.begin(), sys.dofs.end(), m.modes[k]);
            if (it != sys.dofs.end())
                reads.emplace_back(static_cast<int>(it - sys.dofs.begin()), m.weights[k]);
        }
        if (!reads.empty()) points[m.id] = std::move(reads);
    }
    return points;
}

// The string beyond a pressed finger (pressure of ½ or more), on the side away from the bow:
// it rings on its own, and its modes are not the played string's partials.
std::set<std::string> behind_fingers(const Model& model) {
    std::set<std::string> behind;
    std::set<std::string> bowed;
    for (const auto& l : model.lias)
        if (l.kind == LiaKind::BowFriction) bowed.insert(bowed_centre(model, l));
    for (const auto& l : model.lias) {
        if (l.kind != LiaKind::Finger || l.pressure < 0.5 || l.along.size() < 2) continue;
        const FingerContact at = finger_contact(l.finger_position, l.along.size());
        std::size_t bow = l.along.size();
        for (std::size_t i = 0; i < l.along.size(); ++i)
            if (bowed.count(l.along[i])) bow = i;
        if (bow == l.along.size()) continue;  // no bow on this string: nothing to call behind
        for (std::size_t i = 0; i < l.along.size(); ++i)
            if (bow <= at.first ? i > at.first + 1 : i < at.first) behind.insert(l.along[i]);
    }
    return behind;
}

}  // namespace

// Supports are the string behind a finger, and oscillators standing on their own (bridges) or
// read by a body's bridge point;
// the string's modes are those its bowed point reads (any modal point's when nothing bows).
// A support has a spring to ground; a string mass with only a damper to its rest point (σ0
// losses) is still the string.
std::vector<bool> support_dofs(const LinearSystem& sys, const Model& model) {
    std::set<std::string> bowed;
    for (const auto& l : model.lias)
        if (l.kind == LiaKind::BowFriction) bowed.insert(l.to);
    std::set<std::string> string_modes;
    for (const auto& m : model.mats)
        if (m.kind == MatKind::ModalPoint && (bowed.empty() || bowed.count(m.id)))
            string_modes.insert(m.modes.begin(), m.modes.end());
    const std::set<std::string> behind = behind_fingers(model);
    std::vector<bool> support(sys.size(), false);
    for (int i = 0; i < sys.size(); ++i) {
        const Mat* m = model.find_mat(sys.dofs[i]);
        support[i] =
            behind.count(sys.dofs[i]) > 0 ||
            (m && m->kind == MatKind::Oscillator && m->stiffness > 0 && !string_modes.count(m->id));
    }
    return support;
}

void check_analysable(const LinearSystem& sys) {
    const int n = sys.size();
    if (n == 0)
        throw InputError("model",
                         "has no linear part to analyse: no mass with inertia at its fastest rate "
                         "level is joined to springs or dampers");
    if (n > kMaxModalDofs)
        throw InputError("model", "its linear part has " + std::to_string(n) +
                                      " degrees of freedom; modal analysis handles up to " +
                                      std::to_string(kMaxModalDofs));
    for (int i = 0; i < n; ++i)
        if (!(sys.mass[i] > 0.0) || !std::isfinite(sys.mass[i]))
            throw InputError("mass \"" + sys.dofs[i] + "\"",
                             "the mass matrix is singular here (mass " +
                                 format_number(sys.mass[i]) + " kg); give it a positive mass");
}

void refuse_unconverged_analysis() {
    throw InputError("model",
                     "its modal analysis did not converge (the QR iteration ran "
                     "out of steps): check the model's masses and links");
}

ModalAnalysis analyse_modes(const Model& model) {
    return analyse_modes(sounding_part(model), model);
}

ModalAnalysis analyse_modes(const LinearSystem& sys, const Model& model) {
    return class_modes(solve_modes(sys), sys, model);
}

ModalSolve solve_modes_with_eigenvectors(const LinearSystem& sys) {
    check_analysable(sys);
    const int n = sys.size();
    Eigen::EigenSolver<Eigen::MatrixXd> solver(update_matrix(sys), true);
    if (solver.info() != Eigen::Success)  // Eigen then leaves no roots to read
        refuse_unconverged_analysis();
    // Built once: eigenvectors() converts the whole real Schur basis to a complex matrix at
    // every call, which inside a loop cost a quarter of a long string's retuning.
    const Eigen::MatrixXcd vectors = solver.eigenvectors();
    ModalSolve solve;
    std::vector<int> ringing;
    for (int r = 0; r < 2 * n; ++r)  // one of each conjugate pair; real roots do not ring
        if (solver.eigenvalues()[r].imag() > 0.0) ringing.push_back(r);
    solve.roots.resize(static_cast<Eigen::Index>(ringing.size()));
    solve.shapes.resize(n, static_cast<Eigen::Index>(ringing.size()));
    for (std::size_t k = 0; k < ringing.size(); ++k) {
        const auto column = static_cast<Eigen::Index>(k);
        solve.roots[column] = solver.eigenvalues()[ringing[k]];
        solve.shapes.col(column) = vectors.col(ringing[k]).head(n);
    }
    return solve;
}

namespace {

using Complex = std::complex<double>;

// Passes of inverse iteration for a root that two leave short: on a paper string the bridge's
// mode at some 20 Hz lies beside the nut's, and two passes left its shape a thousandth off.
constexpr int kMostPasses = 6;

// How much of the neighbouring mode a shape found for root z may still hold. A shape v = v₁ +
// ε·v₂ (v₂ the mode of the nearest other root, `gap` away) leaves P(z)·v ≈ ε·gap·P′(z)·v₂, so
// ε ≈ |P(z)·v| / (gap·|P′(z)·v|), with P′(z) = 2(z − 1)·M + T²·K + T·Z the pencil's derivative.
// The root's own rounding leaves as much as 1e−15/gap of it: roots closer than about 1e−6 take
// the dense eigenvectors.
constexpr double kMostNeighbourShare = 1e-9;

double neighbour_share(const LinearSystem& sys, Complex z, double gap, const Eigen::VectorXcd& v) {
    // P(z)·v and P′(z)·v from the same products K·v, Z·v and M·v.
    const double t = sys.dt;
    const Eigen::VectorXcd kv = sys.stiffness * v, zv = sys.damping * v;
    const Eigen::VectorXcd mv = sys.mass.cwiseProduct(v);
    const Eigen::VectorXcd pv =
        ((z - 1.0) * (z - 1.0)) * mv + (z * (t * t)) * kv + ((z - 1.0) * t) * zv;
    const Eigen::VectorXcd derivative = (2.0 * (z - 1.0)) * mv + (t * t) * kv + t * zv;
    return pv.norm() / (gap * derivative.norm());  // NaN or infinite where v is lost
}

// The distance from root r to the nearest other root of the update (its conjugate among them).
double nearest_root(const Eigen::VectorXcd& roots, Eigen::Index r) {
    double gap = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < roots.size(); ++j)
        if (j != r) gap = std::min(gap, std::abs(roots[r] - roots[j]));
    return gap;
}

}  // namespace

// Each ringing root's shape by inverse iteration on the pencil at that root (mode_shape()),
// from the roots alone: the roots are the dense solve's to the bit (without eigenvectors Eigen
// runs the same reduction and QR steps and only leaves out their basis), the shapes the same up
// to rounding, and the solve costs about half as much. Nothing where the pencil leaves a force
// out (a finger's, which is in the update alone) or where a shape may hold more than
// kMostNeighbourShare of another mode's (two roots too close, a shape lost to overflow).
std::optional<ModalSolve> solve_modes_from_roots(const LinearSystem& sys) {
    check_analysable(sys);
    if (!sys.fingers.empty()) return std::nullopt;
    const UpdateRoots update = update_roots(sys);
    if (!update.converged) refuse_unconverged_analysis();  // as the dense solve would
    std::vector<Eigen::Index> ringing;
    for (Eigen::Index r = 0; r < update.roots.size(); ++r)
        if (update.roots[r].imag() > 0.0) ringing.push_back(r);  // one of each conjugate pair
    ModalSolve solve;
    solve.roots.resize(static_cast<Eigen::Index>(ringing.size()));
    solve.shapes.resize(sys.size(), static_cast<Eigen::Index>(ringing.size()));
    for (std::size_t k = 0; k < ringing.size(); ++k) {
        const auto column = static_cast<Eigen::Index>(k);
        const Complex z = update.roots[ringing[k]];
        const double gap = nearest_root(update.roots, ringing[k]);
        solve.roots[column] = z;
        bool found = false;
        for (int passes : {2, kMostPasses}) {
            const std::optional<std::vector<Complex>> shape = mode_shape(sys, z, passes);
            if (!shape) return std::nullopt;
            solve.shapes.col(column) =
                Eigen::Map<const Eigen::VectorXcd>(shape->data(), sys.size());
            found = neighbour_share(sys, z, gap, solve.shapes.col(column)) <= kMostNeighbourShare;
            if (found) break;
        }
        if (!found) return std::nullopt;
    }
    return solve;
}

ModalSolve solve_modes(const LinearSystem& sys) {
    if (std::optional<ModalSolve> solve = solve_modes_from_roots(sys)) return std::move(*solve);
    return solve_modes_with_eigenvectors(sys);
}

ModalAnalysis analyse_modes_densely(const LinearSystem& sys, const Model& model) {
    return class_modes(solve_modes_with_eigenvectors(sys), sys, model);
}

ModalAnalysis class_modes(const ModalSolve& solve, const LinearSystem& sys, const Model& model) {
    const int n = sys.size();
    const double dt = sys.dt;
    ModalAnalysis result;
    result.rate = sys.rate;
    result.sample_rate = 1.0 / dt;
    result.dofs = sys.dofs;
    result.points = modal_point_reads(sys, model);
    const std::vector<bool> is_oscillator = support_dofs(sys, model);
    for (Eigen::Index r = 0; r < solve.roots.size(); ++r) {
        const std::complex<double> root = solve.roots[r];
        ModeInfo mode;
        mode.frequency = root_frequency(root, dt);
        mode.t60 = root_t60(root, dt);
        // Shape: the x[n] half of the eigenvector, turned so its largest entry is real.
        Eigen::VectorXcd v = solve.shapes.col(r);
        Eigen::Index top = 0;
        v.cwiseAbs().maxCoeff(&top);
        v *= std::abs(v[top]) / v[top];
        mode.shape.resize(n);
        double kinetic = 0, in_supports = 0;
        for (int i = 0; i < n; ++i) {
            mode.shape[i] = v[i].real() / std::abs(v[top]);
            const double e = sys.mass[i] * std::norm(v[i]);
            kinetic += e;
            if (is_oscillator[i]) in_supports += e;
        }
        mode.support = in_supports > 0.5 * kinetic;
        result.modes.push_back(std::move(mode));
    }
    std::sort(result.modes.begin(), result.modes.end(),
              [](const auto& a, const auto& b) { return a.frequency < b.frequency; });
    int partial = 0;
    for (auto& mode : result.modes) {
        if (mode.support) continue;
        mode.partial = ++partial;
        if (partial == 1) result.fundamental = mode.frequency;
        mode.cents = 1200.0 * std::log2(mode.frequency / (partial * result.fundamental));
    }
    return result;
}

}  // namespace archet
