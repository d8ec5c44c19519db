#include "archet/analysis/modal_analysis.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
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

// Passes of inverse iteration for a root that two leave short: on a paper string the bridge's
// mode at some 20 Hz lies beside the nut's, and two passes left a shape a thousandth off (5e−8
// of the matrix's size in its residual); each pass cuts the other mode's share by the ratio of
// their roots' distances to z.
constexpr int kMostPasses = 6;

// Whether `v` is a null vector of the pencil to within what rounding leaves of one: the dense
// solve's eigenvectors leave up to about 1e−12 of the pencil's size times their own.
bool is_null_vector(const Eigen::SparseMatrix<std::complex<double>>& pencil,
                    const Eigen::VectorXcd& v) {
    const double size = pencil.norm() * v.norm();
    const double residual = (pencil * v).norm();
    return std::isfinite(residual) && size > 0 && residual <= 1e-12 * size;
}

// Each ringing root's shape by inverse iteration on the pencil at that root (mode_shape()),
// from the roots alone: the roots are the dense solve's to the bit (without eigenvectors Eigen
// runs the same reduction and QR steps and only leaves out their basis), the shapes the same up
// to rounding, and the solve costs about half as much. Nothing where a shape is not one root's
// alone (two roots at one frequency), where the pencil leaves a force out (a finger's, which is
// in the update alone), or where a shape is not a null vector of the pencil to rounding (lost to
// overflow, or not converged).
std::optional<ModalSolve> solve_modes_from_roots(const LinearSystem& sys) {
    if (!sys.fingers.empty()) return std::nullopt;
    const UpdateRoots update = update_roots(sys);
    if (!update.converged) refuse_unconverged_analysis();  // as the dense solve would
    std::vector<std::complex<double>> ringing;
    for (const std::complex<double>& z : update.roots)
        if (z.imag() > 0.0) ringing.push_back(z);  // one of each conjugate pair
    std::vector<double> frequencies;
    for (const std::complex<double>& z : ringing) frequencies.push_back(root_frequency(z, sys.dt));
    std::sort(frequencies.begin(), frequencies.end());
    for (std::size_t r = 1; r < frequencies.size(); ++r)
        if (frequencies[r] - frequencies[r - 1] <= 1e-12 * frequencies[r]) return std::nullopt;
    ModalSolve solve;
    solve.roots.resize(static_cast<Eigen::Index>(ringing.size()));
    solve.shapes.resize(sys.size(), static_cast<Eigen::Index>(ringing.size()));
    for (std::size_t k = 0; k < ringing.size(); ++k) {
        const auto column = static_cast<Eigen::Index>(k);
        solve.roots[column] = ringing[k];
        const Eigen::SparseMatrix<std::complex<double>> pencil = quadratic_pencil(sys, ringing[k]);
        bool found = false;
        for (int passes : {2, kMostPasses}) {
            const std::optional<std::vector<std::complex<double>>> shape =
                mode_shape(sys, ringing[k], passes);
            if (!shape) return std::nullopt;
            for (int i = 0; i < sys.size(); ++i) solve.shapes(i, column) = (*shape)[i];
            if ((found = is_null_vector(pencil, solve.shapes.col(column)))) break;
        }
        if (!found) return std::nullopt;
    }
    return solve;
}

}  // namespace

ModalSolve solve_modes(const LinearSystem& sys) {
    check_analysable(sys);
    if (std::optional<ModalSolve> solve = solve_modes_from_roots(sys)) return std::move(*solve);
    return solve_modes_with_eigenvectors(sys);
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
