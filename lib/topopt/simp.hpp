#pragma once
// Minimum-compliance topology optimization under a volume constraint, thesis Sec 2.6.1
// (Eqs 2-48..2-53), by SIMP and the optimality-criteria (OC) update.
//
//   minimize   c(x) = sum_k f_k^T u_k               (Eq 2-50; one term per load case k)
//   subject to K(x) u_k = f_k                        (Eq 2-51, the FE weak form 2-53)
//              sum_e rho_e v_e <= V* sum_e v_e       (Eq 2-52, over the design elements)
//              0 <= x_e <= 1
//
// with the SIMP interpolation of Eq 2-48, E_e = E_min + rho_e^p (E0 - E_min), p = 3,
// E_min = 1e-9 E0 (keeps K regular when elements vanish). Sensitivity
//   dc/drho_e = -p rho_e^(p-1) (E0 - E_min)/E0 sum_k u_ke^T K0_e u_ke.
// OC update (Bendsoe 1995): x_new = clamp(x sqrt(-dc / (lambda dV)), x - m, x + m, 0, 1), with the
// Lagrange multiplier lambda found by bisection so that the volume is met; move limit m = 0.2.
// Converged when max |x_new - x| < 0.01, or stopped at max_iterations.
//
// The sparse pattern of K, the map from element entries to its storage, and the fill-reducing
// ordering + symbolic factorization (Eigen SimplicialLLT, analyzePattern) are done once; every
// iteration only refills the values and factorizes.
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include <Eigen/Dense>

#include "topopt/filter.hpp"
#include "topopt/model.hpp"

namespace fem::topopt {

struct Settings {
    double volume_fraction = 0.5;   // V*: fraction of the design volume kept (thesis: 1 - "reduction")
    double penalty = 3.0;           // p of Eq 2-48 (SIMP)
    double min_stiffness = 1e-9;    // E_min / E0
    FilterKind filter = FilterKind::Sensitivity;
    double filter_radius = 0.0;     // r [m]; required (> 0) unless filter is None
    double move_limit = 0.2;        // m of the OC update
    double change_tolerance = 0.01; // converged when max |x_new - x| < this
    int max_iterations = 200;
    double initial_density = -1;    // < 0: start from V* (a feasible uniform design)
    /// Called after every iteration (progress output); may be empty.
    std::function<void(int iteration, double compliance, double volume, double change)> on_iteration;

    /// Throws InputError naming the parameter when a value is outside its range.
    void validate() const;
};

struct Result {
    std::vector<double> density;     // physical pseudo-densities rho_e of the final design (0..1)
    double final_volume = 0.0;       // its volume fraction of the design region (Eq 2-52)
    std::vector<double> compliance;  // objective of every iteration (of the design analysed then) [J]
    std::vector<double> volume;      // volume fraction of the design region at every iteration
    std::vector<double> change;      // max |x_new - x| of every iteration
    std::vector<double> load_case_compliance;  // of the final analysed design, per load case [J]
    int iterations = 0;
    bool converged = false;
    double seconds = 0.0;            // wall time of optimize()
    double seconds_setup = 0.0;      // of which: sparsity pattern, symbolic factorization, filter matrix
    double seconds_factorizing = 0.0;  // of which: assembly + Cholesky factorization + solves
    /// Wall time per iteration, the one-off setup excluded.
    double seconds_per_iteration() const { return iterations ? (seconds - seconds_setup) / iterations : 0.0; }
};

/// Assembles and solves K(rho) u = f for all load cases of a model. The pattern, the element-to-
/// storage map and the symbolic factorization are built on construction; solve() refills the
/// values, factorizes and back-substitutes. Throws InputError on construction when a load acts on
/// a DOF no element touches, when a load case is zero, and when the fully solid structure is
/// singular (supports that allow a rigid-body motion).
class StiffnessSolver {
public:
    explicit StiffnessSolver(const Model& model);
    ~StiffnessSolver();
    StiffnessSolver(const StiffnessSolver&) = delete;
    StiffnessSolver& operator=(const StiffnessSolver&) = delete;

    /// Solves with element stiffness scale s_e (E_e / E0); returns the displacement vectors (full
    /// size, zero at supports) of every load case.
    const std::vector<Eigen::VectorXd>& solve(const Eigen::VectorXd& scale);
    int free_dof_count() const;
    long long factor_nonzeros() const;  // -1 when the backend does not tell (CHOLMOD)
    /// Wall time spent in solve() so far (assembly + factorization + back-substitution).
    double seconds() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Name of the sparse Cholesky the solver uses ("CHOLMOD supernodal LLT" or Eigen's SimplicialLLT).
const char* cholesky_backend();

/// Objective (Eq 2-50, summed over load cases) and its gradient with respect to the physical
/// densities rho (before filtering), for SIMP with penalty p and E_min ratio.
double compliance_and_gradient(const Model& model, StiffnessSolver& solver, const Eigen::VectorXd& rho,
                               double penalty, double min_stiffness, Eigen::VectorXd& gradient,
                               std::vector<double>* per_case = nullptr);

/// Physical densities of design variables x: passive elements forced to 0 (void) or 1 (solid).
void apply_regions(const Model& model, Eigen::VectorXd& rho);

/// Runs the SIMP/OC loop. Throws InputError for bad settings or a model without load cases.
Result optimize(const Model& model, const Settings& settings);

}  // namespace fem::topopt
