#pragma once
// Modes of a model's linear part, exact for the explicit scheme at its rate: frequency and
// decay from the eigenvalues of the one-step update, shapes as its eigenvectors' (found from each
// root by inverse iteration where that can tell them). Each mode is classed as a partial of the
// string or a mode of its supports (most of its kinetic energy in oscillator MATs, the bridges),
// and partials are measured against n·f1.

#include <Eigen/Dense>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "archet/model/linear_system.hpp"
#include "archet/model/model.hpp"

namespace archet {

struct ModeInfo {
    double frequency = 0;       ///< Hz, exact for the scheme
    double t60 = 0;             ///< s, decay by 60 dB (infinite when undamped)
    bool support = false;       ///< a mode of the bridges rather than of the string
    int partial = 0;            ///< 1, 2, … for string modes; 0 for support modes
    double cents = 0;           ///< partial against partial·f1, cents
    std::vector<double> shape;  ///< at each DOF, real, largest magnitude 1
};

struct ModalAnalysis {
    std::string rate;
    double sample_rate = 0;         ///< of the level analysed
    std::vector<std::string> dofs;  ///< MAT ids
    std::vector<ModeInfo> modes;    ///< by frequency
    double fundamental = 0;         ///< f1, Hz (0 when no string mode)
    /// Modal points: their position as weights on DOFs.
    std::map<std::string, std::vector<std::pair<int, double>>> points;
    /// Shape value of a mode at MAT `id`: a DOF, or a modal point reading DOFs (0 otherwise).
    double shape_at(const ModeInfo& mode, const std::string& id) const;
    bool has_shape_at(const std::string& id) const;
};

/// Largest system analysed: the update matrix is dense, 2·DOFs square.
inline constexpr int kMaxModalDofs = 1500;

/// Analyses the linear part that sounds (around the first output; all of the fastest level
/// without outputs). Throws InputError when there is no linear part or it is too large.
ModalAnalysis analyse_modes(const Model& model);
ModalAnalysis analyse_modes(const LinearSystem& system, const Model& model);

/// The eigenvalue solve of analyse_modes(), apart from what it reads of the model: the roots of
/// the update that ring (one of each conjugate pair, in the solver's order) and their shapes (the
/// x[n] half of their eigenvectors, to a factor), a column each.
struct ModalSolve {
    Eigen::VectorXcd roots;
    Eigen::MatrixXcd shapes;
};
/// Throws what analyse_modes() throws for the system. The shapes come from the roots, a solve
/// each (solve_modes_from_roots()), or else from the dense eigenvectors.
ModalSolve solve_modes(const LinearSystem& system);
/// The same from the dense solve's eigenvectors alone, the shapes' reference (the same roots).
ModalSolve solve_modes_with_eigenvectors(const LinearSystem& system);
/// The shapes from the roots by inverse iteration (solve_modes()' first way), or nothing where
/// that cannot tell a mode's shape from its neighbour's to 1e-9 (see modal_analysis.cpp).
std::optional<ModalSolve> solve_modes_from_roots(const LinearSystem& system);
/// analyse_modes() classing the modes by the dense eigenvectors' shapes: what the builder's fast
/// paths fall back to where they cannot class a mode themselves (string_first_mode(),
/// string_partial_frequencies()), so that what they build does not hang on the inverse iteration.
ModalAnalysis analyse_modes_densely(const LinearSystem& system, const Model& model);
/// The modes of a solve, classed as analyse_modes() classes them for `model`: analyse_modes()
/// is class_modes(solve_modes(system), system, model).
ModalAnalysis class_modes(const ModalSolve& solve, const LinearSystem& system, const Model& model);

/// Throws the InputError analyse_modes() throws for a system it cannot analyse: none, more
/// than kMaxModalDofs, or a mass that is not positive.
void check_analysable(const LinearSystem& system);

/// Throws the InputError analyse_modes() throws when the eigenvalue solve does not converge.
[[noreturn]] void refuse_unconverged_analysis();

/// Which DOFs are supports (oscillators standing on their own such as the bridges, the modes a
/// body's bridge point reads, the string behind a finger): a mode with most of its kinetic energy
/// in them is a support mode.
std::vector<bool> support_dofs(const LinearSystem& system, const Model& model);

}  // namespace archet
