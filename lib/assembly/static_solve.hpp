#pragma once
// Linear static solution K u = f of an assembled model (assembly/model.hpp): the small-load
// reference for nonlinear static solutions (dynamic relaxation on the explicit solver,
// explicit/relaxation.hpp) and for closed-form checks.
#include <vector>

#include "assembly/model.hpp"

namespace fem {

/// Solves K u = f for nodal forces `force` (one Vec3 per mesh node, translations; forces on fixed
/// DOFs are reactions and ignored) with a sparse LDL^T factorization (Eigen SimplicialLDLT, AMD
/// ordering). Returns the nodal translations (zero on fixed DOFs). Throws SolverError when K is
/// singular (a model without enough supports).
std::vector<Vec3> solve_linear_static(const AssembledSystem& system, const std::vector<Vec3>& force);

}  // namespace fem
