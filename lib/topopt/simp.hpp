#pragma once
// Minimum-compliance topology optimization under a volume constraint, thesis Sec 2.6.1
// (Eqs 2-48..2-53), by SIMP and the optimality-criteria (OC) update.
//
//   minimize   c(x) = sum_k f_k^T u_k               (Eq 2-50; one term per load case k)
//   subject to K(x) u_k = f_k                        (Eq 2-51, the FE weak form 2-53)
//              sum_e rho_e v_e <= V* sum_e v_e       (Eq 2-52, over the design elements)
//              0 <= x_e <= 1
//
// with the SIMP interpolation of Eq 2-48 in one of two conventions:
//   modified SIMP (the 88-line code, default): E_e = E_min + rho_e^p (E0 - E_min), E_min = 1e-9 E0;
//   classic SIMP (the 99-line code): E_e = rho_e^p E0 with rho_e >= x_min (e.g. 1e-3);
// p = 3 (both keep K regular when elements vanish). Sensitivity
//   dc/drho_e = -p rho_e^(p-1) (E0 - E_min)/E0 sum_k u_ke^T K0_e u_ke.
// OC update (Bendsoe 1995): x_new = clamp(x sqrt(-dc / (lambda dV)), x - m, x + m, x_min, 1), with
// the Lagrange multiplier lambda found by bisection so that the volume is met; move limit m = 0.2.
// The bisection halves [lo, hi] (geometric mid-point: the scale of dc follows E0 and the loads, from
// kPa tissue to steel) until (hi - lo) / (hi + lo) < oc_tolerance, and keeps the feasible end hi:
// 1e-12 by default (the constraint met to round-off), 1e-3 in the 88-line code. The volume is linear
// in x (V(W x) = (W^T v) . x for the density filter), so the bisection never filters.
// Converged when max |x_new - x| < 0.01, or stopped at max_iterations.
//
// Heaviside projection (Guest, Prevost & Belytschko 2004; the tanh form of Wang, Lazarov & Sigmund
// 2011), on top of the density filter: the physical density is
//   rho = [tanh(beta eta) + tanh(beta (x~ - eta))] / [tanh(beta eta) + tanh(beta (1 - eta))],
// x~ = W x, eta = 0.5: a smoothed step that turns the grey intermediate densities of the filtered
// design into 0 or 1. Continuation: beta starts at 1 and doubles every projection_interval
// iterations, or earlier when the design change falls below change_tolerance, up to
// projection_beta_max; the loop converges only at beta_max, on the change of the projected
// densities (design variables where the step is flat move without changing the structure). The volume of the projected design is
// not linear in x, so then the OC bisection projects at every step.
// With projection the OC move limit applies to the physical densities: m is divided by the step's
// steepest slope H'(eta) = beta / [tanh(beta eta) + tanh(beta (1 - eta))] (1.08 at beta = 1, 16 at
// beta = 32), so that no physical density moves by more than about m per iteration. With the plain
// limit m on x, an element near eta jumps between 0 and 1 in one iteration at beta >= 16: whole
// members flip back and forth, the design never settles and the last bit of a factorization decides
// which of them remain (studies/topology_cases/README.md, "Projected designs").
//
// K u = f is solved by one of two StiffnessSolver back-ends: a sparse Cholesky (CHOLMOD) for small
// and unstructured meshes, or multigrid-preconditioned CG (topopt/multigrid.hpp) on structured grids
// above a size threshold, warm-started from the previous design's displacement. Either way the
// sparse pattern and the map from element entries to its storage are built once; every iteration
// only refills the values.
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "topopt/filter.hpp"
#include "topopt/model.hpp"

namespace fem::topopt {

/// Heaviside projection of the filtered densities (needs FilterKind::Density).
enum class Projection { None, Heaviside };

/// The smoothed Heaviside step of Wang, Lazarov & Sigmund (2011): maps [0, 1] onto [0, 1] with
/// H(0) = 0, H(1) = 1, H(eta) = eta; sharper as beta grows.
struct HeavisideProjection {
    double beta = 1.0, eta = 0.5;
    double operator()(double t) const;
    double slope(double t) const;  // dH/dt
    /// H and dH/dt of every entry, bit-identical to the scalar forms: tanh(beta eta) and the
    /// denominator are the same for all entries and computed once (the OC bisection projects the
    /// whole design ~46 times per iteration, where two of the three tanh per entry were the cost).
    Eigen::VectorXd operator()(const Eigen::VectorXd& t) const;
    Eigen::VectorXd slope(const Eigen::VectorXd& t) const;
};

/// How K u = f is solved: Automatic = multigrid-CG on a structured plane-stress grid with more than
/// Settings::multigrid_threshold free DOF, the direct sparse Cholesky otherwise (shell models on a
/// grid use the multigrid only when asked).
enum class SolverKind { Automatic, Direct, Multigrid };

struct Settings {
    double volume_fraction = 0.5;   // V*: fraction of the design volume kept (thesis: 1 - "reduction")
    double penalty = 3.0;           // p of Eq 2-48 (SIMP)
    double min_stiffness = 1e-9;    // E_min / E0 (modified SIMP); 0 with min_density > 0
    double min_density = 0.0;       // x_min, the lower density bound (classic SIMP); 0: none
    FilterKind filter = FilterKind::Sensitivity;
    double filter_radius = 0.0;     // r [m]; required (> 0) unless filter is None
    Projection projection = Projection::None;
    double projection_beta_max = 32;  // the last continuation step
    int projection_interval = 50;     // iterations per continuation step (at most)
    double move_limit = 0.2;        // m of the OC update
    double change_tolerance = 0.01; // converged when max |x_new - x| < this
    double oc_tolerance = 1e-12;    // OC bisection: relative bracket width (hi - lo) / (hi + lo)
    int max_iterations = 1000;      // the 300 x 100 MBB beam with the density filter needs 837
    double initial_density = -1;    // < 0: start from V* (a feasible uniform design)
    SolverKind solver = SolverKind::Automatic;
    double solver_tolerance = 1e-6; // multigrid-CG: stop at |f - K u| <= this |f|
    int multigrid_threshold = 20000;  // Automatic: multigrid above this many free DOF (on a grid)
    int multigrid_coarsest = 4000;    // multigrid: coarsen until at most this many unknowns remain
    /// Called after every iteration (progress output); may be empty.
    std::function<void(int iteration, double compliance, double volume, double change)> on_iteration;

    /// Throws InputError naming the parameter when a value is outside its range.
    void validate() const;
};

/// Where an optimization spends its time, summed over the iterations [s].
struct Timing {
    double assembly = 0;       // filling K (and the multigrid's Galerkin coarse operators)
    double solve = 0;          // Cholesky factorization + substitution, or the multigrid-CG solve
    double sensitivities = 0;  // compliance and dc/drho, element by element
    double filter = 0;         // density or sensitivity filter (and its chain rule)
    double update = 0;         // OC update with the bisection on lambda
};

struct Result {
    std::vector<double> density;     // physical pseudo-densities rho_e of the final design (0..1)
    double final_volume = 0.0;       // its volume fraction of the design region (Eq 2-52)
    std::vector<double> compliance;  // objective of every iteration (of the design analysed then) [J]
    std::vector<double> volume;      // volume fraction of the design region at every iteration
    std::vector<double> change;      // max |x_new - x| of every iteration (with projection: of rho)
    std::vector<double> beta;        // Heaviside sharpness of every iteration (empty without projection)
    std::vector<double> load_case_compliance;  // of the final analysed design, per load case [J]
    int iterations = 0;
    bool converged = false;
    bool interrupted = false;        // stopped by Ctrl-C (core/progress.hpp) after `iterations`
    double seconds = 0.0;            // wall time of optimize()
    double seconds_setup = 0.0;      // of which: sparsity pattern, symbolic factorization, filter matrix
    Timing timing;                   // of which, per part of an iteration
    std::string solver;              // StiffnessSolver::description()
    long long solver_iterations = 0; // multigrid-CG iterations, all designs and load cases (0: direct)
    /// Wall time per iteration, the one-off setup excluded.
    double seconds_per_iteration() const { return iterations ? (seconds - seconds_setup) / iterations : 0.0; }
};

/// Assembles and solves K(rho) u = f for all load cases of a model, with the back-end that
/// settings.solver selects (the other settings are not used). The pattern, the element-to-storage
/// map and the symbolic factorization (or the multigrid hierarchy) are built on construction;
/// solve() refills the values and solves, the multigrid-CG starting from the previous solution.
/// Throws InputError on construction when a load acts on a DOF no element touches, when a load case
/// is zero, when the fully solid structure is singular (supports that allow a rigid-body motion),
/// and when multigrid is asked for on a mesh that is not a structured grid.
class StiffnessSolver {
public:
    explicit StiffnessSolver(const Model& model, const Settings& settings = Settings());
    ~StiffnessSolver();
    StiffnessSolver(const StiffnessSolver&) = delete;
    StiffnessSolver& operator=(const StiffnessSolver&) = delete;

    /// Solves with element stiffness scale s_e (E_e / E0); returns the displacement vectors (full
    /// size, zero at supports) of every load case.
    const std::vector<Eigen::VectorXd>& solve(const Eigen::VectorXd& scale);
    int free_dof_count() const;
    long long factor_nonzeros() const;  // -1 when the backend does not tell (CHOLMOD)
    /// Wall time spent in solve() so far, in filling the matrices and in solving.
    double assembly_seconds() const;
    double solve_seconds() const;
    bool multigrid() const;
    /// "CHOLMOD supernodal LLT" or "multigrid-CG, 3 levels (coarsest 3952 DOF), tolerance 1e-08".
    std::string description() const;
    /// Multigrid-CG iterations of the last solve(), summed over the load cases (0 for direct).
    int last_iterations() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Name of the sparse Cholesky the solver uses ("CHOLMOD supernodal LLT" or Eigen's SimplicialLLT).
const char* cholesky_backend();

/// Objective (Eq 2-50, summed over load cases) and its gradient with respect to the physical
/// densities rho (before filtering), for SIMP with penalty p and E_min ratio. `seconds_sensitivities`,
/// when given, receives the time spent after the solve.
double compliance_and_gradient(const Model& model, StiffnessSolver& solver, const Eigen::VectorXd& rho,
                               double penalty, double min_stiffness, Eigen::VectorXd& gradient,
                               std::vector<double>* per_case = nullptr, double* seconds_sensitivities = nullptr);

/// Physical densities of design variables x: passive elements forced to `void_density` (0, or x_min
/// with classic SIMP) or 1 (solid).
void apply_regions(const Model& model, Eigen::VectorXd& rho, double void_density = 0.0);

/// Runs the SIMP/OC loop. Throws InputError for bad settings or a model without load cases.
Result optimize(const Model& model, const Settings& settings);

}  // namespace fem::topopt
