#pragma once
// The linear part of a model at one rate level: a diagonal mass matrix and symmetric
// stiffness and damping matrices over the MATs with finite inertia. Fixed and gesture
// points act as ground. The bow module contributes its pressure buffer as if in contact
// (the worst case); its friction is solved implicitly and sets no bound.

#include <Eigen/Sparse>
#include <string>
#include <vector>

#include "archet/model/model.hpp"

namespace archet {

struct LinearSystem {
    std::string rate;                       ///< rate level id
    double dt = 0.0;                        ///< its period, s
    std::vector<std::string> dofs;          ///< MAT ids, one per degree of freedom
    Eigen::VectorXd mass;                   ///< kg
    Eigen::SparseMatrix<double> stiffness;  ///< N/m
    Eigen::SparseMatrix<double> damping;    ///< N·s/m
    int size() const { return static_cast<int>(dofs.size()); }
};

/// Assembles the linear system of links at `rate` (and oscillator grounds of MATs at it).
/// With `rate` empty, uses the fastest level. Assumes the model's references are valid.
LinearSystem assemble_linear_system(const Model& model, const std::string& rate = "");

/// The connected part of a system that holds `dof` (all of it when `dof` is not in it).
LinearSystem connected_part(const LinearSystem& system, const std::string& dof);

/// The linear part that sounds: the connected part around the first audio output (the
/// string and its bridges, without the bow's own resonances), at the fastest rate level.
LinearSystem sounding_part(const Model& model);

}  // namespace archet
