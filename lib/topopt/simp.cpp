#include "topopt/simp.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include <Eigen/SparseCholesky>
#ifdef FEM_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif
#ifdef _OPENMP
#include <omp.h>
#endif
#include <fmt/format.h>

#include "core/error.hpp"

namespace fem::topopt {

namespace {
#ifdef FEM_HAVE_CHOLMOD
using Cholesky = Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>;
constexpr const char* kCholesky = "CHOLMOD supernodal LLT";
#else
using Cholesky = Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>;
constexpr const char* kCholesky = "Eigen SimplicialLLT (AMD)";
#endif
}  // namespace

const char* cholesky_backend() { return kCholesky; }

namespace {
// Debian's CHOLMOD 3 runs parts of the supernodal factorization with a compiled-in team of 4 OpenMP
// threads. On a small shared machine (2 cores here, several jobs) that oversubscribes the cores and
// the threads spend their time spinning: measured 2-3x slower than one thread. So the library
// factorizes serially: this guard makes OpenMP regions inactive while CHOLMOD runs and restores the
// caller's setting afterwards.
struct SerialOpenMP {
#ifdef _OPENMP
    int saved = omp_get_max_active_levels();
    SerialOpenMP() { omp_set_max_active_levels(0); }
    ~SerialOpenMP() { omp_set_max_active_levels(saved); }
#endif
};
}  // namespace

void Settings::validate() const {
    if (!(volume_fraction > 0 && volume_fraction < 1))
        throw InputError(fmt::format("volume fraction must lie in (0, 1), got {} (it is the fraction of the "
                                     "design volume kept: a 70 % reduction is 0.3)", volume_fraction));
    if (!(penalty >= 1)) throw InputError(fmt::format("SIMP penalty must be >= 1, got {}", penalty));
    if (!(min_stiffness > 0 && min_stiffness < 1))
        throw InputError(fmt::format("minimum stiffness ratio E_min/E0 must lie in (0, 1), got {}", min_stiffness));
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
    Eigen::SparseMatrix<double> K;      // lower triangle of K over the free DOF (column-major)
    std::vector<int> slot;              // element entry (e, a, b) -> index into K's values, -1 if none
    Eigen::MatrixXd F, U;               // loads and displacements over the free DOF, one column per case
    std::vector<Eigen::VectorXd> u;     // full displacement vectors
    double seconds = 0;
    Cholesky llt;

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

StiffnessSolver::StiffnessSolver(const Model& model) : impl_(std::make_unique<Impl>(model)) {
    auto& I = *impl_;
    const int ndof = model.dof_count();
    const int nd = model.dofs_per_element;
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

    // Pattern of the lower triangle, built once.
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(static_cast<std::size_t>(model.element_count()) * nd * (nd + 1) / 2);
    for (int e = 0; e < model.element_count(); ++e) {
        auto dofs = model.dofs(e);
        for (int a = 0; a < nd; ++a)
            for (int b = 0; b < nd; ++b) {
                const int r = I.free_of[dofs[a]], c = I.free_of[dofs[b]];
                if (r >= 0 && c >= 0 && r >= c) t.emplace_back(r, c, 1.0);
            }
    }
    I.K.resize(I.n_free, I.n_free);
    I.K.setFromTriplets(t.begin(), t.end());
    I.K.makeCompressed();
    // Where each element entry (a, b) lands in K's value array (-1: supported DOF or upper triangle).
    I.slot.assign(static_cast<std::size_t>(model.element_count()) * nd * nd, -1);
    const int* outer = I.K.outerIndexPtr();
    const int* inner = I.K.innerIndexPtr();
    for (int e = 0; e < model.element_count(); ++e) {
        auto dofs = model.dofs(e);
        for (int b = 0; b < nd; ++b)
            for (int a = 0; a < nd; ++a) {
                const int r = I.free_of[dofs[a]], c = I.free_of[dofs[b]];
                if (r < 0 || c < 0 || r < c) continue;
                const int* pos = std::lower_bound(inner + outer[c], inner + outer[c + 1], r);
                I.slot[static_cast<std::size_t>(e) * nd * nd + static_cast<std::size_t>(b) * nd + a] =
                    static_cast<int>(pos - inner);
            }
    }
    I.F.resize(I.n_free, static_cast<Eigen::Index>(model.loads.size()));
    for (std::size_t k = 0; k < model.loads.size(); ++k)
        for (int d = 0; d < ndof; ++d)
            if (I.free_of[d] >= 0) I.F(I.free_of[d], static_cast<Eigen::Index>(k)) = model.loads[k](d);
    I.u.assign(model.loads.size(), Eigen::VectorXd::Zero(ndof));

    // Symbolic analysis (AMD ordering, elimination tree) once.
    SerialOpenMP serial;
    I.llt.analyzePattern(I.K);

    // The fully solid structure must be regular: with a rigid-body motion left free (or a part of
    // the mesh hanging loose) K is singular, and the Cholesky factorization either fails or has a
    // round-off pivot that makes the response to a generic load astronomically large. A regular
    // FE stiffness has |u| |K|_max / |f| of the order of its condition number (< 1e10 for any
    // reasonable mesh); a singular one gives ~1e15 and more.
    I.fill(Eigen::VectorXd::Ones(model.element_count()));
    I.llt.factorize(I.K);
    bool singular = I.llt.info() != Eigen::Success;
    if (!singular) {
        Eigen::VectorXd f(I.n_free);
        for (int i = 0; i < I.n_free; ++i) f(i) = 1.0 + 0.5 * std::sin(1.7 * i);  // generic, deterministic
        const Eigen::VectorXd u = I.llt.solve(f);
        const double kmax = I.K.coeffs().cwiseAbs().maxCoeff();
        const double ratio = u.norm() * kmax / f.norm();
        singular = !std::isfinite(ratio) || ratio > 1e13;
    }
    if (singular)
        throw InputError("topology model: the stiffness matrix of the solid design is singular: the supports do "
                         "not prevent every rigid-body motion (or part of the mesh is disconnected)");
}

StiffnessSolver::~StiffnessSolver() = default;
int StiffnessSolver::free_dof_count() const { return impl_->n_free; }
long long StiffnessSolver::factor_nonzeros() const {
#ifdef FEM_HAVE_CHOLMOD
    return -1;  // Eigen's CHOLMOD wrapper does not expose the factor
#else
    return impl_->llt.matrixL().nestedExpression().nonZeros();
#endif
}

double StiffnessSolver::seconds() const { return impl_->seconds; }

const std::vector<Eigen::VectorXd>& StiffnessSolver::solve(const Eigen::VectorXd& scale) {
    auto& I = *impl_;
    const auto t0 = std::chrono::steady_clock::now();
    I.fill(scale);
    SerialOpenMP serial;
    I.llt.factorize(I.K);
    if (I.llt.info() != Eigen::Success)
        throw SolverError("topology optimization: Cholesky factorization of K failed (matrix not positive definite)");
    I.U = I.llt.solve(I.F);
    const int ndof = I.model.dof_count();
    for (std::size_t k = 0; k < I.u.size(); ++k)
        for (int d = 0; d < ndof; ++d)
            I.u[k](d) = I.free_of[d] >= 0 ? I.U(I.free_of[d], static_cast<Eigen::Index>(k)) : 0.0;
    I.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return I.u;
}

// --- objective and sensitivities -------------------------------------------------------------------

double compliance_and_gradient(const Model& model, StiffnessSolver& solver, const Eigen::VectorXd& rho, double p,
                               double emin, Eigen::VectorXd& gradient, std::vector<double>* per_case) {
    const int ne = model.element_count(), nd = model.dofs_per_element;
    Eigen::VectorXd scale(ne);
    for (int e = 0; e < ne; ++e) scale(e) = emin + std::pow(rho(e), p) * (1.0 - emin);  // Eq 2-48 (SIMP)
    const auto& u = solver.solve(scale);
    gradient.setZero(ne);
    double c = 0;
    if (per_case) per_case->clear();
    Eigen::VectorXd ue(nd), ku(nd);
    for (std::size_t k = 0; k < u.size(); ++k) {
        const double ck = model.loads[k].dot(u[k]);  // Eq 2-50: the work of the loads
        c += ck;
        if (per_case) per_case->push_back(ck);
        for (int e = 0; e < ne; ++e) {
            auto dofs = model.dofs(e);
            for (int a = 0; a < nd; ++a) ue(a) = u[k](dofs[a]);
            ku.noalias() = model.stiffness(e).selfadjointView<Eigen::Lower>() * ue;
            const double energy = ue.dot(ku);  // u_e^T K0_e u_e
            gradient(e) -= p * std::pow(rho(e), p - 1) * (1.0 - emin) * energy;
        }
    }
    return c;
}

void apply_regions(const Model& model, Eigen::VectorXd& rho) {
    for (int e = 0; e < model.element_count(); ++e) {
        if (model.region[e] == Region::Void) rho(e) = 0.0;
        else if (model.region[e] == Region::Solid) rho(e) = 1.0;
    }
}

// --- the optimization loop -------------------------------------------------------------------------

Result optimize(const Model& model, const Settings& s) {
    s.validate();
    const auto t0 = std::chrono::steady_clock::now();
    const int ne = model.element_count();
    if (static_cast<int>(model.region.size()) != ne) throw InputError("topology model: one region flag per element expected");
    StiffnessSolver solver(model);

    // Design region volume (Eq 2-52 is written over the design elements: passive ones are fixed).
    Eigen::VectorXd v_design = Eigen::VectorXd::Zero(ne);
    for (int e = 0; e < ne; ++e)
        if (model.region[e] == Region::Design) v_design(e) = model.volume[e];
    const double V = v_design.sum();
    if (!(V > 0)) throw InputError("topology model: no design element (every element is passive)");

    std::optional<Filter> filter;
    if (s.filter != FilterKind::None) filter.emplace(model.centroid, model.volume, s.filter_radius);
    const bool density_filter = s.filter == FilterKind::Density;

    Eigen::VectorXd x = Eigen::VectorXd::Constant(ne, s.initial_density > 0 ? s.initial_density : s.volume_fraction);
    apply_regions(model, x);
    auto physical = [&](const Eigen::VectorXd& design) {
        Eigen::VectorXd rho = density_filter ? filter->densities(design) : design;
        apply_regions(model, rho);
        return rho;
    };

    Result r;
    r.seconds_setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double solve_setup = solver.seconds();
    Eigen::VectorXd rho = physical(x), dc, dv, xnew(ne);
    for (int it = 1; it <= s.max_iterations; ++it) {
        const double c = compliance_and_gradient(model, solver, rho, s.penalty, s.min_stiffness, dc, &r.load_case_compliance);
        dv = v_design;
        if (density_filter) {
            dc = filter->backward(dc);
            dv = filter->backward(dv);
        } else if (s.filter == FilterKind::Sensitivity) {
            dc = filter->sensitivities(x, dc);
        }
        r.compliance.push_back(c);
        r.volume.push_back(rho.dot(v_design) / V);

        // OC update with bisection on the Lagrange multiplier (in log space: the scale of dc
        // follows E0 and the loads, from kPa tissue to steel).
        double gmax = 0;
        for (int e = 0; e < ne; ++e)
            if (model.region[e] == Region::Design && dv(e) > 0) gmax = std::max(gmax, -dc(e) / dv(e));
        if (!(gmax > 0)) throw SolverError("topology optimization: the loads do no work on any design element");
        double lo = gmax * 1e-40, hi = gmax * 1e10;
        auto update = [&](double lambda) {
            for (int e = 0; e < ne; ++e) {
                if (model.region[e] != Region::Design) { xnew(e) = x(e); continue; }
                const double B = dv(e) > 0 ? std::max(0.0, -dc(e)) / (lambda * dv(e)) : 0.0;
                const double lower = std::max(0.0, x(e) - s.move_limit), upper = std::min(1.0, x(e) + s.move_limit);
                xnew(e) = std::clamp(x(e) * std::sqrt(B), lower, upper);
            }
            return physical(xnew).dot(v_design) / V;
        };
        while (hi / lo > 1 + 1e-12) {
            const double mid = std::sqrt(lo * hi);
            if (update(mid) > s.volume_fraction) lo = mid;
            else hi = mid;
        }
        update(hi);  // the feasible side of the bracket
        const double change = (xnew - x).cwiseAbs().maxCoeff();
        x = xnew;
        rho = physical(x);
        r.change.push_back(change);
        r.iterations = it;
        if (s.on_iteration) s.on_iteration(it, c, r.volume.back(), change);
        if (change < s.change_tolerance) {
            r.converged = true;
            break;
        }
    }
    r.density.assign(rho.data(), rho.data() + ne);
    r.final_volume = rho.dot(v_design) / V;
    r.seconds_factorizing = solver.seconds() - solve_setup;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
}

}  // namespace fem::topopt
