#pragma once
// The linear part of a model at one rate level: a diagonal mass matrix and symmetric
// stiffness and damping matrices over the MATs with finite inertia. Fixed and gesture
// points act as ground. The bow module contributes its pressure buffer as if in contact
// (the worst case); its friction is solved implicitly and sets no bound. A finger is a
// spring and damper from its contact point to ground, at its pressure, kept apart from the
// matrices: the scheme solves it implicitly (update_matrix() does the same), so it bounds no
// step and the stability check leaves it out.

#include <Eigen/Sparse>
#include <string>
#include <vector>

#include "archet/model/model.hpp"

namespace archet {

/// A finger's spring and damper (SI, its pressure applied) from the point Σ weight·x(dof) to
/// ground.
struct FingerTerm {
    std::vector<std::pair<int, double>> point;
    double stiffness = 0, damping = 0;
};

struct LinearSystem {
    std::string rate;                       ///< rate level id
    double dt = 0.0;                        ///< its period, s
    std::vector<std::string> dofs;          ///< MAT ids, one per degree of freedom
    Eigen::VectorXd mass;                   ///< kg
    Eigen::SparseMatrix<double> stiffness;  ///< N/m
    Eigen::SparseMatrix<double> damping;    ///< N·s/m
    std::vector<FingerTerm> fingers;        ///< in the order the scheme solves them
    int size() const { return static_cast<int>(dofs.size()); }
};

enum class Fingers { Include, Exclude };

/// Assembles the linear system of links at `rate` (and oscillator grounds of MATs at it).
/// With `rate` empty, uses the fastest level. Assumes the model's references are valid.
LinearSystem assemble_linear_system(const Model& model, const std::string& rate = "",
                                    Fingers fingers = Fingers::Include);

/// Whether every link of the system joins neighbours in the order of its DOFs (a chain: its
/// stiffness and damping tridiagonal).
bool is_tridiagonal(const LinearSystem& system);

/// Whether two systems are the same to the bit: rate, period, DOFs, matrices and fingers (an
/// analysis of one is the other's).
bool identical(const LinearSystem& a, const LinearSystem& b);

/// The connected part of a system that holds `dof` (all of it when `dof` is not in it).
LinearSystem connected_part(const LinearSystem& system, const std::string& dof);

/// The linear part that sounds: the connected part around the first audio output (the
/// string and its bridges, without the bow's own resonances), at the fastest rate level.
LinearSystem sounding_part(const Model& model);

}  // namespace archet
