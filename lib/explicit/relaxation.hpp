#pragma once
// Dynamic relaxation: the large-deformation static equilibrium of a model under dead loads, found
// by running the explicit solver with critical mass-proportional damping of the first mode
// (alpha = 2 omega_1, Eq 2-39: zeta_1 = alpha / (2 omega_1) = 1) until the motion has died out.
// Used for the single-limb force-displacement curves of thesis Table 5-2, which the thesis
// computed with a nonlinear static ANSYS solve.
//
// The loads are applied in stages (load factors f_1 < f_2 < ..., each times the given nodal
// forces): within a stage the factor moves from the previous one to the new one along a smooth
// ramp (ramp_periods periods of the first mode), then held; the stage has converged when the
// kinetic energy has fallen below ke_fraction x the largest kinetic energy of that stage. The
// displacement field is recorded and the next stage starts from it. A stage that does not converge
// within max_stage_periods periods is a SolverError.
//
// Convergence: with zeta_1 = 1 the first mode's error decays as exp(-omega_1 t); modes above are
// underdamped (zeta_k = omega_1 / omega_k) and die out through the tetrahedra's bulk viscosity and
// the optional stiffness damping. The number of steps per stage is ~ (omega_max / omega_1) times a
// few: stiff, nearly incompressible rubber (nu = 0.49) costs many steps.
//
// The relaxed state is that of the explicit elements (neo-Hookean, large rotations); verify it at
// a small load against the linear static solution of the same mesh (study chicken_shackling).
#include <vector>

#include "explicit/solver.hpp"

namespace fem {

struct RelaxationOptions {
    double omega_1 = 0.0;             // first natural frequency [rad/s] (e.g. modal::solve_modes)
    double ke_fraction = 1e-6;        // stage converged: kinetic energy < this x the stage's peak
    double ramp_periods = 1.0;        // load ramp per stage, in periods 2 pi / omega_1
    double max_stage_periods = 40.0;  // give up after this many periods in one stage
    double samples_per_period = 40.0; // how often the kinetic energy is checked
    ExplicitOptions solver{};         // end_time, history and observer settings are set by relax()
};

struct RelaxationStage {
    double load_factor = 0.0;
    double time = 0.0;            // when it converged [s]
    double peak_kinetic = 0.0;    // largest kinetic energy of the stage [J]
    double final_kinetic = 0.0;   // kinetic energy when it converged [J]
    std::vector<Vec3> displacement;  // every node, x - X
};

struct RelaxationResult {
    std::vector<RelaxationStage> stages;
    RunSummary summary;
};

/// Relaxes `model` (its supports set; no other time-dependent loads) under the dead nodal force
/// `force_per_node` on every node of `nodes`, scaled by each of `load_factors` in turn. Sets the
/// global mass damping of the model to 2 omega_1. Throws InputError for bad options, SolverError
/// when a stage does not converge.
RelaxationResult relax(ExplicitModel& model, const std::vector<int>& nodes, const Vec3& force_per_node,
                       const std::vector<double>& load_factors, const RelaxationOptions& options);

}  // namespace fem
