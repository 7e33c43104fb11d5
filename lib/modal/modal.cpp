#include "modal/modal.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <numbers>
#include <sstream>

#include <memory>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#ifdef FEM_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif
#include <Spectra/SymGEigsShiftSolver.h>
#include <fmt/format.h>

#include "assembly/model.hpp"
#include "core/eigen_instances.hpp"
#include "core/error.hpp"
#include "core/memory.hpp"
#include "io/hdf5.hpp"
#include "io/table.hpp"
#include "io/vtu.hpp"
#include "mesh/mesh.hpp"

namespace fem::modal {
namespace {

using SpMat = Eigen::SparseMatrix<double>;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// y = (K - sigma M)^{-1} x: the interface Spectra's shift-and-invert mode asks of its OpType. K and M
// share one pattern (lower triangles), so K - sigma M is formed on the values directly. Two
// factorizations: CHOLMOD's supernodal LL^T (BLAS-3 on dense fronts, the fast one for 3D solids;
// needs K - sigma M positive definite, i.e. sigma below the lowest eigenvalue) when the library was
// built with it, else Eigen's SimplicialLDLT (AMD ordering), which also takes an indefinite matrix.
class ShiftInvert {
public:
    using Scalar = double;
    ShiftInvert(const SpMat& k, const SpMat& m, bool prefer_cholmod) : k_(k), m_(m), prefer_cholmod_(prefer_cholmod) {}
    Eigen::Index rows() const { return k_.rows(); }
    Eigen::Index cols() const { return k_.rows(); }

    void set_shift(double sigma) {
        SpMat a = k_;
        if (sigma != 0.0) a -= sigma * m_;  // both lower triangles
#ifdef FEM_HAVE_CHOLMOD
        if (prefer_cholmod_ && sigma <= 0.0) {
            cholmod_ = std::make_unique<Eigen::CholmodSupernodalLLT<SpMat, Eigen::Lower>>();
            cholmod_->cholmod().print = 0;  // failures are reported by the exception below, not on stdout
            cholmod_->compute(a);
            if (cholmod_->info() != Eigen::Success)
                throw InputError(fmt::format("K - sigma M is not positive definite at sigma = {:g}: model has rigid-body "
                                             "modes: add supports or use shift (a negative shift_hz)",
                                             sigma));
            nonzeros_ = static_cast<long long>(cholmod_->cholmod().lnz);
            backend_ = "CHOLMOD supernodal LL^T";
            return;
        }
#endif
        ldlt_ = std::make_unique<Eigen::SimplicialLDLT<SpMat, Eigen::Lower>>();
        ldlt_->compute(a);
        if (ldlt_->info() != Eigen::Success && sigma > 0)
            throw InputError(fmt::format("factorization of K - sigma M failed at sigma = {:g} rad^2/s^2: the shift ({:g} Hz) "
                                         "is at an eigenvalue of the model; move shift_hz away from it",
                                         sigma, std::sqrt(sigma) / (2 * std::numbers::pi)));
        if (ldlt_->info() != Eigen::Success)
            throw InputError("factorization of K - sigma M failed (sigma = " + fmt::format("{:g}", sigma) +
                             "): model has rigid-body modes: add supports or use shift");
        // A zero pivot (relative to the largest) means K - sigma M is singular: with sigma = 0 the
        // model can move as a rigid body (or a mechanism). Count them for the message.
        const Eigen::VectorXd& d = ldlt_->vectorD();
        const double dmax = d.cwiseAbs().maxCoeff();
        int tiny = 0;
        for (Eigen::Index i = 0; i < d.size(); ++i)
            if (std::abs(d(i)) <= 1e-11 * dmax) ++tiny;
        if (tiny > 0 && sigma > 0)
            throw InputError(fmt::format("K - sigma M is singular at sigma = {:g} rad^2/s^2 ({} zero pivots): the shift "
                                         "({:g} Hz) is at an eigenvalue of the model; move shift_hz away from it",
                                         sigma, tiny, std::sqrt(sigma) / (2 * std::numbers::pi)));
        if (tiny > 0)
            throw InputError(fmt::format("K - sigma M is singular at sigma = {:g} ({} zero pivots): model has rigid-body "
                                         "modes: add supports or use shift (a negative shift_hz)",
                                         sigma, tiny));
        nonzeros_ = ldlt_->matrixL().nestedExpression().nonZeros() + d.size();
        backend_ = "Eigen SimplicialLDLT";
    }
    void perform_op(const double* x_in, double* y_out) const {
        Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
        Eigen::Map<Eigen::VectorXd> y(y_out, rows());
#ifdef FEM_HAVE_CHOLMOD
        if (cholmod_) {
            y = cholmod_->solve(x);
            ++ops_;
            return;
        }
#endif
        y = ldlt_->solve(x);
        ++ops_;
    }
    long long operations() const { return ops_; }
    long long nonzeros() const { return nonzeros_; }
    const char* backend() const { return backend_; }

private:
    const SpMat& k_;
    const SpMat& m_;
    bool prefer_cholmod_;
    std::unique_ptr<Eigen::SimplicialLDLT<SpMat, Eigen::Lower>> ldlt_;
#ifdef FEM_HAVE_CHOLMOD
    std::unique_ptr<Eigen::CholmodSupernodalLLT<SpMat, Eigen::Lower>> cholmod_;
#endif
    mutable long long ops_ = 0;
    long long nonzeros_ = 0;
    const char* backend_ = "";
};

// y = M x with the lower triangle of M.
class MassProduct {
public:
    using Scalar = double;
    explicit MassProduct(const SpMat& m) : m_(m) {}
    Eigen::Index rows() const { return m_.rows(); }
    Eigen::Index cols() const { return m_.rows(); }
    void perform_op(const double* x_in, double* y_out) const {
        Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
        Eigen::Map<Eigen::VectorXd> y(y_out, rows());
        y.noalias() = m_.selfadjointView<Eigen::Lower>() * x;
    }

private:
    const SpMat& m_;
};

}  // namespace

Conditioning::Conditioning(const SpMat& K, const SpMat& M) {
    for (Eigen::Index i = 0; i < K.nonZeros(); ++i) k_finite = k_finite && std::isfinite(K.valuePtr()[i]);
    for (Eigen::Index i = 0; i < M.nonZeros(); ++i) m_finite = m_finite && std::isfinite(M.valuePtr()[i]);
    k_min = m_min = std::numeric_limits<double>::infinity();
    int first_non_finite = -1;  // reported as the largest stiffness
    for (Eigen::Index j = 0; j < K.rows(); ++j) {
        const double k = K.coeff(j, j), m = M.coeff(j, j);
        if (!std::isfinite(k) && first_non_finite < 0) first_non_finite = static_cast<int>(j);
        if (k > 0 && k < k_min) k_min = k, dof_k_min = static_cast<int>(j);
        if (k > 0 && k > k_max) k_max = k, dof_k_max = static_cast<int>(j);
        if (m > 0 && m < m_min) m_min = m, dof_m_min = static_cast<int>(j);
        if (m > 0 && m > m_max) m_max = m, dof_m_max = static_cast<int>(j);
        if (m > 0) lambda_max = std::max(lambda_max, k / m);
    }
    if (first_non_finite >= 0) dof_k_max = first_non_finite;
}

bool Conditioning::representable() const { return k_finite && m_finite && lambda_max < 1e300; }

std::string Conditioning::describe() const {
    return fmt::format("stiffness diagonal from {:.3g} to {:.3g} (ratio {:.3g}), mass diagonal from {:.3g} to {:.3g} "
                       "(ratio {:.3g}), largest K_ii / M_ii {:.3g} rad^2/s^2",
                       k_min, k_max, k_max / k_min, m_min, m_max, m_max / m_min, lambda_max);
}

namespace {

// The dense fallback of a small model whose Lanczos run broke down: a singular mass (CalculiX's C3D8I
// puts none on some combinations of its bubble and nodal DOFs) bounds the Krylov space of
// (K - sigma M)^-1 M by the rank of M, and a basis larger than that (a model of a few elements)
// breaks down. With K - sigma M = L L^T, the eigenvalues mu of L^-1 M L^-T are 1 / (lambda - sigma),
// mu = 0 for the massless directions (lambda infinite). Returns false when the model is too large
// for dense matrices, K - sigma M is not positive definite (a shift inside the spectrum) or it has
// fewer finite eigenvalues than asked; fills r.eigenvalues (ascending) and r.shapes otherwise.
bool dense_modes(const SpMat& K, const SpMat& M, int modes, ModalResult& r) {
    const Eigen::Index n = K.rows();
    if (n > 2000) return false;
    const Eigen::MatrixXd Md = Eigen::MatrixXd(M).selfadjointView<Eigen::Lower>();
    const Eigen::MatrixXd A = Eigen::MatrixXd(Eigen::MatrixXd(K).selfadjointView<Eigen::Lower>()) - r.shift * Md;
    const Eigen::LLT<Eigen::MatrixXd> llt(A);
    if (llt.info() != Eigen::Success) return false;
    Eigen::MatrixXd C = llt.matrixL().solve(Md);
    C = llt.matrixL().solve(Eigen::MatrixXd(C.transpose()));
    const Eigen::MatrixXd symmetric = 0.5 * (C + C.transpose());  // a named matrix: core/eigen_instances.hpp
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(symmetric);
    if (es.info() != Eigen::Success) return false;
    const Eigen::VectorXd& mu = es.eigenvalues();  // ascending: the largest mu (nearest the shift) last
    if (!(mu(n - modes) > 1e-12 * std::abs(mu(n - 1)))) return false;
    r.eigenvalues.resize(modes);
    r.shapes.resize(n, modes);
    for (int k = 0; k < modes; ++k) {
        r.eigenvalues(k) = r.shift + 1.0 / mu(n - 1 - k);
        r.shapes.col(k) = llt.matrixU().solve(es.eigenvectors().col(n - 1 - k));
    }
    r.factorization = "dense LL^T (Lanczos broke down)";
    return true;
}

}  // namespace

ModalResult solve_modes(const SpMat& K, const SpMat& M, const ModalOptions& o) {
    const int n = static_cast<int>(K.rows());
    if (K.rows() != K.cols() || M.rows() != n || M.cols() != n) throw InputError("modal: K and M must be square and of equal size");
    if (o.modes < 1) throw InputError("modal: number of modes must be at least 1, got " + std::to_string(o.modes));
    if (o.modes >= n)
        throw InputError(fmt::format("modal: {} modes asked but the model has only {} free DOFs", o.modes, n));
    ModalResult r;
    r.shift = (o.shift_hz < 0 ? -1.0 : 1.0) * std::pow(2 * std::numbers::pi * o.shift_hz, 2);
    if (!std::isfinite(r.shift))
        throw InputError(fmt::format("modal: shift_hz = {:g} Hz gives the shift sigma = {:g} rad^2/s^2, not a finite number",
                                     o.shift_hz, r.shift));
    const int ncv = std::min(n, o.basis > 0 ? std::max(o.basis, o.modes + 1) : std::max(2 * o.modes + 1, o.modes + 16));
    // The Lanczos basis (n x ncv) and the modes (n x modes) are dense.
    require_memory(8.0 * n * (ncv + o.modes) * 2, fmt::format("a modal solve of {} modes on {} DOFs (Lanczos basis {})",
                                                              o.modes, n, ncv));

    // Values that double precision cannot carry through the solve are named before it starts.
    const Conditioning cond(K, M);
    if (!cond.k_finite)
        throw InputError("modal: the stiffness matrix holds non-finite entries (an overflow: is a Young's modulus or a "
                         "thickness far too large for SI units, Pa and m?)");
    if (!cond.m_finite)
        throw InputError("modal: the mass matrix holds non-finite entries (an overflow: is a density far too large for SI "
                         "units, kg/m^3?)");
    if (!(cond.lambda_max < 1e300))
        throw InputError(fmt::format("modal: the eigenvalues overflow double precision: {} (is a density far too small "
                                     "or a Young's modulus far too large for SI units?)", cond.describe()));

    // A shift that dwarfs every K_ii / M_ii leaves K in the round-off of K - sigma M (at 1e10 x, that
    // round-off is already 1e-6 of the highest eigenvalue): the shift is what is wrong, not the model.
    if (std::abs(r.shift) > 1e10 * cond.lambda_max && cond.lambda_max > 0)
        throw InputError(fmt::format("modal: shift_hz = {:g} Hz gives the shift sigma = {:.3g} rad^2/s^2, {:.3g} x the "
                                     "largest K_ii / M_ii ({:.3g} rad^2/s^2, about the highest eigenvalue): K is lost in "
                                     "the round-off of K - sigma M; use |shift_hz| below {:.3g} Hz",
                                     o.shift_hz, r.shift, std::abs(r.shift) / cond.lambda_max, cond.lambda_max,
                                     std::sqrt(cond.lambda_max) / (2 * std::numbers::pi)));
    if (o.shift_hz == 0.0 && o.admit_rigid_body_modes) r.shift = -1e-8 * cond.lambda_max;

    auto t0 = Clock::now();
    ShiftInvert op(K, M, o.use_cholmod);
    MassProduct bop(M);
    using Solver = Spectra::SymGEigsShiftSolver<ShiftInvert, MassProduct, Spectra::GEigsMode::ShiftInvert>;
    std::optional<Solver> solver;
    Eigen::Index nconv = 0;
    std::string lanczos_failure;
    try {
        // The constructor factorizes K - sigma M (through set_shift).
        solver.emplace(op, bop, o.modes, ncv, r.shift);
        r.factor_seconds = seconds_since(t0);
        r.factor_nonzeros = op.nonzeros();
        r.factorization = op.backend();
        t0 = Clock::now();
        solver->init();
        // Largest |1 / (lambda - sigma)| = eigenvalues nearest the shift; returned in ascending lambda.
        nconv = solver->compute(Spectra::SortRule::LargestMagn, o.max_iterations, o.tolerance, Spectra::SortRule::SmallestAlge);
        if (solver->info() != Spectra::CompInfo::Successful || nconv < o.modes)
            lanczos_failure = fmt::format("Lanczos converged {} of {} modes in {} restarts (basis {}); raise max_iterations or "
                                          "the basis size ({})",
                                          nconv, o.modes, solver->num_iterations(), ncv, cond.describe());
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {  // Spectra's own failures (a tridiagonal eigensolve that does not converge)
        lanczos_failure = fmt::format("the eigensolver failed ({}); the problem is ill-conditioned: {}", e.what(), cond.describe());
    }
    r.solve_seconds = seconds_since(t0);
    if (lanczos_failure.empty()) {
        r.iterations = static_cast<int>(solver->num_iterations());
        r.operations = op.operations();
        r.eigenvalues = solver->eigenvalues();
        r.shapes = solver->eigenvectors();
    } else if (!dense_modes(K, M, o.modes, r)) {
        throw SolverError("modal: " + lanczos_failure);
    }
    if (r.shift == 0.0) {
        // A factorization can pass a singular K when round-off leaves its zero pivots slightly
        // positive; the zero eigenvalues then show up here. The scale is the largest K_ii / M_ii
        // (about the highest element eigenvalue).
        double scale = 0.0;
        for (int j = 0; j < n; ++j)
            if (M.coeff(j, j) > 0) scale = std::max(scale, K.coeff(j, j) / M.coeff(j, j));
        int rigid = 0;
        for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k) rigid += std::abs(r.eigenvalues(k)) < 1e-12 * scale;
        if (rigid > 0)
            throw InputError(fmt::format("{} eigenvalues are zero at the round-off level: model has rigid-body modes: add "
                                         "supports or use shift (a negative shift_hz)",
                                         rigid));
    }
    r.frequencies_hz.resize(o.modes);
    r.residuals.resize(o.modes);
    const auto Ks = K.selfadjointView<Eigen::Lower>();
    double k_norm = 0.0;  // ||K||_1 of the symmetric matrix (max column sum), for rigid modes
    {
        Eigen::VectorXd colsum = Eigen::VectorXd::Zero(n);
        for (int j = 0; j < n; ++j)
            for (SpMat::InnerIterator it(K, j); it; ++it) {
                colsum(j) += std::abs(it.value());
                if (it.row() != j) colsum(it.row()) += std::abs(it.value());
            }
        k_norm = colsum.maxCoeff();
    }
    const auto Ms = M.selfadjointView<Eigen::Lower>();
    for (int k = 0; k < o.modes; ++k) {
        Eigen::VectorXd phi = r.shapes.col(k);
        Eigen::VectorXd mphi = Ms * phi;
        const double scale = 1.0 / std::sqrt(phi.dot(mphi));
        // Deterministic sign: the largest component positive.
        Eigen::Index imax;
        phi.cwiseAbs().maxCoeff(&imax);
        const double sign = phi(imax) < 0 ? -1.0 : 1.0;
        phi *= sign * scale;
        mphi *= sign * scale;
        r.shapes.col(k) = phi;
        const double lambda = r.eigenvalues(k);
        const Eigen::VectorXd kphi = Ks * phi;
        // ||K phi|| normally; for a rigid-body mode (lambda below the shift's magnitude) K phi is
        // itself round-off, so the backward error relative to ||K||_1 ||phi|| is reported instead.
        // (stableNorm: with a tiny modulus, E = 1e-200 Pa, the plain sum of squares underflows to 0/0.)
        const double denom = std::abs(lambda) >= std::abs(r.shift) ? kphi.stableNorm() : k_norm * phi.stableNorm();
        r.residuals(k) = (kphi - lambda * mphi).stableNorm() / denom;
        r.frequencies_hz(k) = (lambda < 0 ? -1.0 : 1.0) * std::sqrt(std::abs(lambda)) / (2 * std::numbers::pi);
    }
    return r;
}

ModalResult solve_modes(const AssembledSystem& system, const ModalOptions& options) {
    return solve_modes(system.stiffness, system.mass, options);
}

Eigen::MatrixXd mac(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    if (a.rows() != b.rows()) throw InputError("MAC: mode sets have different DOF counts");
    const Eigen::MatrixXd ab = a.transpose() * b;
    const Eigen::VectorXd aa = a.colwise().squaredNorm(), bb = b.colwise().squaredNorm();
    Eigen::MatrixXd m(a.cols(), b.cols());
    for (Eigen::Index i = 0; i < a.cols(); ++i)
        for (Eigen::Index j = 0; j < b.cols(); ++j) m(i, j) = ab(i, j) * ab(i, j) / (aa(i) * bb(j));
    return m;
}

Eigen::MatrixXd mac(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const SpMat& mass) {
    if (a.rows() != b.rows() || a.rows() != mass.rows()) throw InputError("MAC: mode sets and mass have different DOF counts");
    const Eigen::MatrixXd mb = mass.selfadjointView<Eigen::Lower>() * b;
    const Eigen::MatrixXd ma = mass.selfadjointView<Eigen::Lower>() * a;
    const Eigen::MatrixXd ab = a.transpose() * mb;
    Eigen::MatrixXd m(a.cols(), b.cols());
    for (Eigen::Index i = 0; i < a.cols(); ++i)
        for (Eigen::Index j = 0; j < b.cols(); ++j)
            m(i, j) = ab(i, j) * ab(i, j) / (a.col(i).dot(ma.col(i)) * b.col(j).dot(mb.col(j)));
    return m;
}

std::vector<ModePair> pair_modes(const Eigen::MatrixXd& m, double min_mac) {
    std::vector<ModePair> all;
    for (Eigen::Index i = 0; i < m.rows(); ++i)
        for (Eigen::Index j = 0; j < m.cols(); ++j)
            all.push_back({static_cast<int>(i), static_cast<int>(j), m(i, j)});
    // Largest MAC first; ties by index so the result is deterministic.
    std::stable_sort(all.begin(), all.end(), [](const ModePair& x, const ModePair& y) { return x.mac > y.mac; });
    std::vector<char> used_a(m.rows(), 0), used_b(m.cols(), 0);
    std::vector<ModePair> pairs;
    for (const ModePair& p : all) {
        if (p.mac < min_mac) break;
        if (used_a[p.a] || used_b[p.b]) continue;
        used_a[p.a] = used_b[p.b] = 1;
        pairs.push_back(p);
    }
    std::sort(pairs.begin(), pairs.end(), [](const ModePair& x, const ModePair& y) { return x.a < y.a; });
    return pairs;
}

void write_results(const std::filesystem::path& dir, const Mesh& mesh, const AssembledSystem& system, const ModalResult& r,
                   int shapes) {
    const int nm = static_cast<int>(r.eigenvalues.size());
    const int written = shapes < 0 ? nm : std::min(shapes, nm);
    std::vector<double> mode(nm), f(r.frequencies_hz.data(), r.frequencies_hz.data() + nm),
        lam(r.eigenvalues.data(), r.eigenvalues.data() + nm), res(r.residuals.data(), r.residuals.data() + nm);
    for (int k = 0; k < nm; ++k) mode[k] = k + 1;
    io::Table t;
    t.add("mode", mode).add("frequency_hz", f).add("eigenvalue", lam).add("residual", res);
    io::write_csv(dir / "frequencies.csv", t);

    io::H5Writer h5(dir / "modes.h5");
    h5.write("frequencies_hz", f);
    h5.write("eigenvalues", lam);
    h5.write("residuals", res);
    Eigen::MatrixXd xyz(mesh.node_count(), 3);
    for (int i = 0; i < mesh.node_count(); ++i) xyz.row(i) = mesh.nodes[i].transpose();
    h5.write("nodes", xyz);
    h5.attribute("/", "shift_rad2_per_s2", r.shift);
    h5.attribute("/", "normalization", "mass (phi^T M phi = 1)");
    h5.attribute("/", "shapes_written", static_cast<double>(written));
    std::optional<io::PvdSeries> pvd;
    if (written > 0) pvd.emplace(dir / "modes.pvd");
    for (int k = 0; k < written; ++k) {
        const std::vector<double> u = system.translations(r.shapes.col(k));
        h5.write(fmt::format("mode_{}/translation", k + 1),
                 Eigen::MatrixXd(Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(u.data(), mesh.node_count(), 3)));
        h5.attribute(fmt::format("mode_{}", k + 1), "frequency_hz", f[k]);
        io::VtuData data;
        data.point_fields.push_back({"mode_shape", 3, u});
        pvd->add(k + 1, mesh, data);  // "time" = mode number, so ParaView steps through the modes
    }
    h5.commit();
}

std::string summary(const AssembledSystem& system, const ModalResult& r) {
    std::ostringstream s;
    s << fmt::format("modal: {} nodes, {} DOFs ({} fixed, {} coupled out), {} equations{}\n", system.dofs.node_count(),
                     system.dofs.size(), system.reduction.fixed, system.reduction.coupled, system.size(),
                     system.internal_dofs > 0 ? fmt::format(" ({} of them element-internal)", system.internal_dofs) : "");
    s << fmt::format("  K nonzeros (lower) {}, factor nonzeros {}, shift {:g} rad^2/s^2\n", system.stiffness.nonZeros(),
                     r.factor_nonzeros, r.shift);
    s << fmt::format("  factorization ({}) {:.3f} s, Lanczos {:.3f} s ({} restarts, {} solves)\n", r.factorization, r.factor_seconds, r.solve_seconds,
                     r.iterations, r.operations);
    s << "  mode  frequency [Hz]  residual\n";
    for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k)
        s << fmt::format("  {:4d}  {:14.6g}  {:.2e}\n", k + 1, r.frequencies_hz(k), r.residuals(k));
    return s.str();
}

}  // namespace fem::modal
