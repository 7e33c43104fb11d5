#include "topopt/simp.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/progress.hpp"
#include "topopt/multigrid.hpp"
#include "topopt/sparse_assembly.hpp"

namespace fem::topopt {

using detail::Cholesky;
using detail::SerialOpenMP;

const char* cholesky_backend() { return detail::kCholesky; }

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

void Settings::validate() const {
    if (!(volume_fraction > 0 && volume_fraction < 1))
        throw InputError(fmt::format("volume fraction must lie in (0, 1), got {} (it is the fraction of the "
                                     "design volume kept: a 70 % reduction is 0.3)", volume_fraction));
    if (!(penalty >= 1)) throw InputError(fmt::format("SIMP penalty must be >= 1, got {}", penalty));
    if (!(min_stiffness >= 0 && min_stiffness < 1))
        throw InputError(fmt::format("minimum stiffness ratio E_min/E0 must lie in [0, 1), got {}", min_stiffness));
    if (!(min_density >= 0 && min_density < volume_fraction))
        throw InputError(fmt::format("minimum density x_min must lie in [0, volume fraction {}), got {}", volume_fraction, min_density));
    if (min_stiffness == 0 && min_density == 0)
        throw InputError("give a minimum stiffness ratio E_min/E0 > 0 or a minimum density x_min > 0 (K must stay regular)");
    if (!(oc_tolerance > 0 && oc_tolerance < 0.1))
        throw InputError(fmt::format("OC bisection tolerance must lie in (0, 0.1), got {}", oc_tolerance));
    if (projection != Projection::None && filter != FilterKind::Density)
        throw InputError("the Heaviside projection acts on density-filtered designs: set the filter to density");
    if (projection != Projection::None && !(projection_beta_max >= 1 && projection_interval >= 1))
        throw InputError(fmt::format("projection: beta_max must be >= 1 (got {}) and the interval >= 1 (got {})",
                                     projection_beta_max, projection_interval));
    if (!(solver_tolerance > 0 && solver_tolerance < 1))
        throw InputError(fmt::format("solver tolerance must lie in (0, 1), got {}", solver_tolerance));
    if (filter != FilterKind::None && !(filter_radius > 0))
        throw InputError(fmt::format("filter radius must be > 0 for a sensitivity or density filter, got {}", filter_radius));
    if (!(move_limit > 0 && move_limit <= 1)) throw InputError(fmt::format("move limit must lie in (0, 1], got {}", move_limit));
    if (!(change_tolerance > 0)) throw InputError(fmt::format("change tolerance must be > 0, got {}", change_tolerance));
    if (max_iterations < 1) throw InputError(fmt::format("max iterations must be >= 1, got {}", max_iterations));
    if (initial_density >= 0 && !(initial_density > 0 && initial_density <= 1))
        throw InputError(fmt::format("initial density must lie in (0, 1], got {}", initial_density));
}

// --- assembly and solution -------------------------------------------------------------------------

struct StiffnessSolver::Impl {
    const Model& model;
    std::vector<int> free_of;           // global DOF -> free index, -1 when supported or unused
    int n_free = 0;
    Eigen::MatrixXd F, U;               // loads and displacements over the free DOF, one column per case
    std::vector<Eigen::VectorXd> u;     // full displacement vectors
    double seconds_assembly = 0, seconds_solve = 0;
    int last_iterations = 0;
    // Direct back-end: the lower triangle of K over the free DOF, element entry -> value slot.
    Eigen::SparseMatrix<double> K;
    std::vector<int> slot;
    Cholesky llt;
    // Multigrid back-end.
    std::unique_ptr<GridMultigrid> mg;
    double tolerance = 0;

    explicit Impl(const Model& m) : model(m) {}
    void fill(const Eigen::VectorXd& scale);
};

void StiffnessSolver::Impl::fill(const Eigen::VectorXd& scale) {
    double* values = K.valuePtr();
    std::fill(values, values + K.nonZeros(), 0.0);
    const int nd = model.dofs_per_element;
    const std::size_t per = static_cast<std::size_t>(nd) * nd;
    for (int e = 0; e < model.element_count(); ++e) {
        const double s = scale(e);
        const double* k0 = model.stiffness(e).data();  // column-major nd x nd, symmetric
        const int* sl = slot.data() + per * e;
        for (std::size_t i = 0; i < per; ++i)
            if (sl[i] >= 0) values[sl[i]] += s * k0[i];
    }
}

StiffnessSolver::StiffnessSolver(const Model& model, const Settings& settings) : impl_(std::make_unique<Impl>(model)) {
    auto& I = *impl_;
    const int ndof = model.dof_count();
    if (model.loads.empty()) throw InputError("topology model: no load case");
    if (static_cast<int>(model.fixed.size()) != ndof) throw InputError("topology model: support flags do not match the DOF count");

    // Free DOF: not supported and touched by at least one element.
    std::vector<char> used(ndof, 0);
    for (int d : model.element_dofs) used[d] = 1;
    I.free_of.assign(ndof, -1);
    for (int d = 0; d < ndof; ++d)
        if (used[d] && !model.fixed[d]) I.free_of[d] = I.n_free++;
    for (std::size_t k = 0; k < model.loads.size(); ++k) {
        const auto& f = model.loads[k];
        if (f.size() != ndof) throw InputError(fmt::format("load case {}: force vector has {} entries, the model {} DOF", k + 1, f.size(), ndof));
        if (f.cwiseAbs().maxCoeff() == 0.0) throw InputError(fmt::format("load case {} applies no force", k + 1));
        for (int d = 0; d < ndof; ++d)
            if (f(d) != 0.0 && !used[d])
                throw InputError(fmt::format("load case {}: force on node {} (component {}), which belongs to no element",
                                             k + 1, d / model.dofs_per_node, d % model.dofs_per_node));
    }
    if (I.n_free == 0) throw InputError("topology model: every DOF is supported: nothing to solve");
    I.F = Eigen::MatrixXd::Zero(I.n_free, static_cast<Eigen::Index>(model.loads.size()));
    for (std::size_t k = 0; k < model.loads.size(); ++k)
        for (int d = 0; d < ndof; ++d)
            if (I.free_of[d] >= 0) I.F(I.free_of[d], static_cast<Eigen::Index>(k)) = model.loads[k](d);
    I.U = Eigen::MatrixXd::Zero(I.n_free, I.F.cols());
    I.u.assign(model.loads.size(), Eigen::VectorXd::Zero(ndof));

    const bool multigrid = settings.solver == SolverKind::Multigrid ||
                           (settings.solver == SolverKind::Automatic && model.grid && model.dofs_per_node == 2 &&
                            I.n_free > settings.multigrid_threshold);  // shells: only when asked (untimed)
    SerialOpenMP serial;
    const Eigen::VectorXd solid = Eigen::VectorXd::Ones(model.element_count());
    bool regular = true;
    if (multigrid) {
        I.mg = std::make_unique<GridMultigrid>(model, I.free_of, I.n_free, settings.multigrid_coarsest);  // InputError without a grid
        I.tolerance = settings.solver_tolerance;
        // A singular fine operator (a free rigid-body motion, which bilinear interpolation
        // represents) makes the Galerkin coarse operator singular too: the check is on the coarsest.
        regular = I.mg->set_scale(solid);
    } else {
        std::vector<int> unknowns(model.element_dofs.size());
        for (std::size_t k = 0; k < unknowns.size(); ++k) unknowns[k] = I.free_of[model.element_dofs[k]];
        detail::build_pattern(I.n_free, model.dofs_per_element, unknowns, /*lower_only=*/true, I.K, I.slot);
        I.llt.analyzePattern(I.K);  // AMD ordering, elimination tree: once
        I.fill(solid);
        regular = detail::factorize_regular(I.llt, I.K);
    }
    if (!regular)
        throw InputError("topology model: the stiffness matrix of the solid design is singular: the supports do "
                         "not prevent every rigid-body motion (or part of the mesh is disconnected)");
}

StiffnessSolver::~StiffnessSolver() = default;
int StiffnessSolver::free_dof_count() const { return impl_->n_free; }
long long StiffnessSolver::factor_nonzeros() const {
#ifdef FEM_HAVE_CHOLMOD
    return -1;  // Eigen's CHOLMOD wrapper does not expose the factor
#else
    return impl_->mg ? -1 : impl_->llt.matrixL().nestedExpression().nonZeros();
#endif
}
double StiffnessSolver::assembly_seconds() const { return impl_->seconds_assembly; }
double StiffnessSolver::solve_seconds() const { return impl_->seconds_solve; }
bool StiffnessSolver::multigrid() const { return impl_->mg != nullptr; }
int StiffnessSolver::last_iterations() const { return impl_->last_iterations; }
std::string StiffnessSolver::description() const {
    if (!impl_->mg) return cholesky_backend();
    return fmt::format("multigrid-CG, {} levels (coarsest {} DOF: {}), tolerance {:g}", impl_->mg->levels(),
                       impl_->mg->coarsest_unknowns(), cholesky_backend(), impl_->tolerance);
}

const std::vector<Eigen::VectorXd>& StiffnessSolver::solve(const Eigen::VectorXd& scale) {
    auto& I = *impl_;
    SerialOpenMP serial;
    auto t0 = Clock::now();
    I.last_iterations = 0;
    if (I.mg) {
        if (!I.mg->set_scale(scale))
            throw SolverError("topology optimization: Cholesky factorization of the coarsest multigrid level failed");
        I.seconds_assembly += since(t0);
        t0 = Clock::now();
        for (Eigen::Index k = 0; k < I.F.cols(); ++k) {
            Eigen::VectorXd uk = I.U.col(k);  // warm start: the previous design's displacement
            I.last_iterations += I.mg->solve(I.F.col(k), uk, I.tolerance);
            I.U.col(k) = uk;
        }
    } else {
        I.fill(scale);
        I.seconds_assembly += since(t0);
        t0 = Clock::now();
        I.llt.factorize(I.K);
        if (I.llt.info() != Eigen::Success)
            throw SolverError("topology optimization: Cholesky factorization of K failed (matrix not positive definite)");
        I.U = I.llt.solve(I.F);
    }
    const int ndof = I.model.dof_count();
    for (std::size_t k = 0; k < I.u.size(); ++k)
        for (int d = 0; d < ndof; ++d)
            I.u[k](d) = I.free_of[d] >= 0 ? I.U(I.free_of[d], static_cast<Eigen::Index>(k)) : 0.0;
    I.seconds_solve += since(t0);
    return I.u;
}

// --- objective and sensitivities -------------------------------------------------------------------

namespace {
// energy(e) += u_e^T K0_e u_e for every element; ND = dofs_per_element when fixed at compile time
// (8: quad4 plane stress, 16: quad8, 24: shell) for speed, Eigen::Dynamic otherwise.
template <int ND>
void add_element_energies(const Model& model, const Eigen::VectorXd& u, Eigen::VectorXd& energy) {
    const int nd = model.dofs_per_element;
    Eigen::Matrix<double, ND, 1> ue(nd);
    for (int e = 0; e < model.element_count(); ++e) {
        const int* dofs = model.element_dofs.data() + static_cast<std::size_t>(e) * nd;
        for (int a = 0; a < nd; ++a) ue(a) = u(dofs[a]);
        const Eigen::Map<const Eigen::Matrix<double, ND, ND>> K0(model.stiffness(e).data(), nd, nd);
        energy(e) += ue.dot(K0 * ue);
    }
}
}  // namespace

double compliance_and_gradient(const Model& model, StiffnessSolver& solver, const Eigen::VectorXd& rho, double p,
                               double emin, Eigen::VectorXd& gradient, std::vector<double>* per_case,
                               double* seconds_sensitivities) {
    const int ne = model.element_count();
    Eigen::VectorXd scale(ne);
    for (int e = 0; e < ne; ++e) scale(e) = emin + std::pow(rho(e), p) * (1.0 - emin);  // Eq 2-48 (SIMP)
    const auto& u = solver.solve(scale);
    const auto t0 = Clock::now();
    Eigen::VectorXd energy = Eigen::VectorXd::Zero(ne);  // sum_k u_ke^T K0_e u_ke
    double c = 0;
    if (per_case) per_case->clear();
    for (std::size_t k = 0; k < u.size(); ++k) {
        const double ck = model.loads[k].dot(u[k]);  // Eq 2-50: the work of the loads
        c += ck;
        if (per_case) per_case->push_back(ck);
        switch (model.dofs_per_element) {
            case 8: add_element_energies<8>(model, u[k], energy); break;
            case 16: add_element_energies<16>(model, u[k], energy); break;
            case 24: add_element_energies<24>(model, u[k], energy); break;
            default: add_element_energies<Eigen::Dynamic>(model, u[k], energy);
        }
    }
    gradient.resize(ne);
    for (int e = 0; e < ne; ++e) gradient(e) = -p * std::pow(rho(e), p - 1) * (1.0 - emin) * energy(e);
    if (seconds_sensitivities) *seconds_sensitivities = since(t0);
    return c;
}

// The step and its slope share two constants, a = tanh(beta eta) and the denominator
// d = a + tanh(beta (1 - eta)); the scalar and vector forms evaluate the same expressions.
namespace {
struct StepConstants {
    double a, d;
    explicit StepConstants(const HeavisideProjection& H)
        : a(std::tanh(H.beta * H.eta)), d(std::tanh(H.beta * H.eta) + std::tanh(H.beta * (1 - H.eta))) {}
};
double step_value(const HeavisideProjection& H, const StepConstants& k, double t) {
    return (k.a + std::tanh(H.beta * (t - H.eta))) / k.d;
}
double step_slope(const HeavisideProjection& H, const StepConstants& k, double t) {
    const double th = std::tanh(H.beta * (t - H.eta));
    return H.beta * (1 - th * th) / k.d;
}
}  // namespace

double HeavisideProjection::operator()(double t) const { return step_value(*this, StepConstants(*this), t); }
double HeavisideProjection::slope(double t) const { return step_slope(*this, StepConstants(*this), t); }

Eigen::VectorXd HeavisideProjection::operator()(const Eigen::VectorXd& t) const {
    const StepConstants k(*this);
    Eigen::VectorXd h(t.size());
    for (Eigen::Index i = 0; i < t.size(); ++i) h(i) = step_value(*this, k, t(i));
    return h;
}

Eigen::VectorXd HeavisideProjection::slope(const Eigen::VectorXd& t) const {
    const StepConstants k(*this);
    Eigen::VectorXd s(t.size());
    for (Eigen::Index i = 0; i < t.size(); ++i) s(i) = step_slope(*this, k, t(i));
    return s;
}

void apply_regions(const Model& model, Eigen::VectorXd& rho, double void_density) {
    for (int e = 0; e < model.element_count(); ++e) {
        if (model.region[e] == Region::Void) rho(e) = void_density;
        else if (model.region[e] == Region::Solid) rho(e) = 1.0;
    }
}

// --- the optimization loop -------------------------------------------------------------------------

Result optimize(const Model& model, const Settings& s) {
    s.validate();
    SerialOpenMP serial;
    const auto t0 = Clock::now();
    const int ne = model.element_count();
    if (static_cast<int>(model.region.size()) != ne) throw InputError("topology model: one region flag per element expected");
    StiffnessSolver solver(model, s);

    // Design region volume (Eq 2-52 is written over the design elements: passive ones are fixed).
    Eigen::VectorXd v_design = Eigen::VectorXd::Zero(ne);
    for (int e = 0; e < ne; ++e)
        if (model.region[e] == Region::Design) v_design(e) = model.volume[e];
    const double V = v_design.sum();
    if (!(V > 0)) throw InputError("topology model: no design element (every element is passive)");

    std::optional<Filter> filter;
    if (s.filter != FilterKind::None) filter.emplace(model.centroid, model.volume, s.filter_radius);
    const bool density_filter = s.filter == FilterKind::Density;
    const bool projected = s.projection == Projection::Heaviside;
    const double x_min = s.min_density;

    HeavisideProjection project{1.0, 0.5};  // beta grows by continuation
    double& beta = project.beta;

    Eigen::VectorXd x = Eigen::VectorXd::Constant(ne, s.initial_density > 0 ? s.initial_density : s.volume_fraction);
    apply_regions(model, x, x_min);
    Eigen::VectorXd filtered;  // W x of the design analysed (projection only)
    auto physical = [&](const Eigen::VectorXd& design) {
        Eigen::VectorXd rho = density_filter ? filter->densities(design) : design;
        if (projected) {
            filtered = rho;
            rho = project(filtered);
        }
        apply_regions(model, rho, x_min);
        return rho;
    };
    // Without projection the volume is linear in the design variables: V(rho(x)) = dv . x with
    // dv = v_design, or W^T v_design for the density filter (passive elements carry no design
    // volume). With projection, dv is the chain rule at the current design.
    Eigen::VectorXd dv = density_filter ? filter->backward(v_design) : v_design;

    Result r;
    r.solver = solver.description();
    r.seconds_setup = since(t0);
    Eigen::VectorXd rho = physical(x), dc, xnew(ne), lower(ne), upper(ne), step(ne);
    int iterations_at_beta = 0;
    for (int it = 1; it <= s.max_iterations; ++it) {
        const double assembly0 = solver.assembly_seconds(), solve0 = solver.solve_seconds();
        double t_sens = 0;
        const double c = compliance_and_gradient(model, solver, rho, s.penalty, s.min_stiffness, dc,
                                                 &r.load_case_compliance, &t_sens);
        r.timing.assembly += solver.assembly_seconds() - assembly0;
        r.timing.solve += solver.solve_seconds() - solve0;
        r.timing.sensitivities += t_sens;
        r.solver_iterations += solver.last_iterations();
        auto t = Clock::now();
        if (projected) {  // chain rule through the projection, then the filter
            const Eigen::VectorXd slope = project.slope(filtered);
            dc = filter->backward(dc.cwiseProduct(slope));
            dv = filter->backward(v_design.cwiseProduct(slope));
        } else if (density_filter) {
            dc = filter->backward(dc);
        } else if (s.filter == FilterKind::Sensitivity) {
            dc = filter->sensitivities(x, dc);
        }
        r.timing.filter += since(t);
        r.compliance.push_back(c);
        r.volume.push_back(rho.dot(v_design) / V);

        // OC update: x_new = clamp(step_e / sqrt(lambda), lower_e, upper_e), step_e = x_e sqrt(-dc_e / dv_e),
        // with the bisection on lambda.
        t = Clock::now();
        double gmax = 0;
        // With projection the limit is on the physical densities: m over the step's steepest slope
        // (header): m / 1.08 at beta = 1, m / 16 at beta = 32.
        const double move = projected ? s.move_limit / std::max(1.0, project.slope(project.eta)) : s.move_limit;
        for (int e = 0; e < ne; ++e) {
            const bool design = model.region[e] == Region::Design && dv(e) > 0;
            const double g = design ? std::max(0.0, -dc(e)) / dv(e) : 0.0;
            gmax = std::max(gmax, g);
            step(e) = design ? x(e) * std::sqrt(g) : x(e);
            lower(e) = design ? std::max(x_min, x(e) - move) : x(e);
            upper(e) = design ? std::min(1.0, x(e) + move) : x(e);
        }
        if (!(gmax > 0)) throw SolverError("topology optimization: the loads do no work on any design element");
        auto update = [&](double lambda) {
            const double k = 1.0 / std::sqrt(lambda);
            for (int e = 0; e < ne; ++e) xnew(e) = std::clamp(step(e) * k, lower(e), upper(e));
            return projected ? physical(xnew).dot(v_design) / V : xnew.dot(dv) / V;
        };
        double lo = gmax * 1e-40, hi = gmax * 1e10;
        while ((hi - lo) > s.oc_tolerance * (hi + lo)) {
            const double mid = std::sqrt(lo * hi);
            if (update(mid) > s.volume_fraction) lo = mid;
            else hi = mid;
        }
        update(hi);  // the feasible side of the bracket
        double change = (xnew - x).cwiseAbs().maxCoeff();
        x = xnew;
        r.timing.update += since(t);
        t = Clock::now();
        const Eigen::VectorXd rho_old = rho;
        rho = physical(x);
        // With projection, design variables in the flat parts of the step move without changing the
        // structure (and keep moving by the move limit): the change that counts is the physical one.
        if (projected) change = (rho - rho_old).cwiseAbs().maxCoeff();
        r.timing.filter += since(t);
        r.change.push_back(change);
        r.iterations = it;
        if (s.on_iteration) s.on_iteration(it, c, r.volume.back(), change);
        // Ctrl-C under an InterruptGuard (core/progress.hpp): stop with the design reached.
        if (interrupt_requested()) {
            r.interrupted = true;
            break;
        }
        if (projected) {
            r.beta.push_back(beta);
            // Continuation: sharpen when the design has settled or the step has lasted long enough.
            if (beta < s.projection_beta_max && (change < s.change_tolerance || ++iterations_at_beta >= s.projection_interval)) {
                beta = std::min(2 * beta, s.projection_beta_max);
                iterations_at_beta = 0;
                rho = physical(x);
                continue;
            }
        }
        if (change < s.change_tolerance) {
            r.converged = true;
            break;
        }
    }
    r.density.assign(rho.data(), rho.data() + ne);
    r.final_volume = rho.dot(v_design) / V;
    r.seconds = since(t0);
    return r;
}

}  // namespace fem::topopt
