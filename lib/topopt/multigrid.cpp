#include "topopt/multigrid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "core/error.hpp"
#include "topopt/sparse_assembly.hpp"

namespace fem::topopt {

namespace {

using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// Coarsening of a line of n cells: ceil(n / 2) coarse cells; coarse line I lies on fine line
// min(2 I, n) (a last odd cell stays one cell wide).
int coarse_cells(int n) { return (n + 1) / 2; }
int fine_line(int I, int n) { return std::min(2 * I, n); }

// The coarse lines (index, weight) that interpolate fine line i (bilinear = product of two of these).
std::array<std::pair<int, double>, 2> line_weights(int i, int n) {
    if (i % 2 == 0) return {{{i / 2, 1.0}, {-1, 0.0}}};
    if (i == n) return {{{coarse_cells(n), 1.0}, {-1, 0.0}}};
    return {{{(i - 1) / 2, 0.5}, {(i + 1) / 2, 0.5}}};
}

}  // namespace

// One level of the hierarchy. In a named namespace, not the file's anonymous one: GridMultigrid::Impl
// (a class with external linkage) holds them, and GCC warns (-Wsubobject-linkage) when such a class has
// a member of a file-local type that a unity build includes like a header.
namespace detail {
struct Level {
    int nx = 0, ny = 0;
    std::vector<int> dof_of_point;  // lattice point -> its node's first DOF (level 0: model numbering)
    std::vector<int> free_of;       // level DOF -> unknown index, -1 when supported
    int n = 0;                      // unknowns
    int nd = 0;                     // DOF per element
    std::vector<int> element_unknowns;  // nd per element (levels >= 1: cell j nx + i, corners SW SE NE NW)
    RowMajor A;                     // both triangles
    std::vector<int> slot, diag;
    std::vector<Eigen::MatrixXd> K;  // levels >= 1: cell matrices
    // Levels >= 1: the (up to 4) cells of the finer level inside each cell, and the index of the
    // matrix that carries a child's matrix to this cell (level 1: G = P_c^T K0 P_c; deeper: P_c).
    std::vector<std::array<std::pair<int, int>, 4>> children;
    std::vector<Eigen::MatrixXd> transfer;
    RowMajor P, R;                  // to/from the next coarser level
    Eigen::VectorXd x, b, r;
};
}  // namespace detail

namespace {

using detail::Level;

// Refills the level's matrix from its element matrices: element_matrix(e) = {scale, column-major data}.
void fill(Level& L, const auto& element_matrix) {
    double* v = L.A.valuePtr();
    std::fill(v, v + L.A.nonZeros(), 0.0);
    const std::size_t per = static_cast<std::size_t>(L.nd) * L.nd;
    for (std::size_t e = 0; e < L.element_unknowns.size() / L.nd; ++e) {
        const int* sl = L.slot.data() + per * e;
        const auto [scale, m] = element_matrix(e);
        if (scale == 0.0) continue;
        for (std::size_t i = 0; i < per; ++i)
            if (sl[i] >= 0) v[sl[i]] += scale * m[i];
    }
}

// The row products s_i = (A x)_i of a row-major matrix, handed to store(i, s_i).
template <class Store>
void csr_rows(const RowMajor& A, const double* x, Store store) {
    const int* outer = A.outerIndexPtr();
    const int* inner = A.innerIndexPtr();
    const double* v = A.valuePtr();
    for (Eigen::Index i = 0; i < A.rows(); ++i) {
        double s = 0;
        for (int k = outer[i]; k < outer[i + 1]; ++k) s += v[k] * x[inner[k]];
        store(i, s);
    }
}
// y = A x;  y += A x;  r = b - A x (each one pass).
void csr_multiply(const RowMajor& A, const double* x, double* y) { csr_rows(A, x, [y](Eigen::Index i, double s) { y[i] = s; }); }
void csr_multiply_add(const RowMajor& A, const double* x, double* y) { csr_rows(A, x, [y](Eigen::Index i, double s) { y[i] += s; }); }
void csr_residual(const RowMajor& A, const double* x, const double* b, double* r) {
    csr_rows(A, x, [b, r](Eigen::Index i, double s) { r[i] = b[i] - s; });
}

// A forward Gauss-Seidel sweep for A x = b from x = 0: the entries right of the diagonal multiply
// zeros, so only the lower triangle is read.
void gauss_seidel_from_zero(const RowMajor& A, const std::vector<int>& diag, const double* b, double* x) {
    const int* outer = A.outerIndexPtr();
    const int* inner = A.innerIndexPtr();
    const double* v = A.valuePtr();
    for (Eigen::Index i = 0; i < A.rows(); ++i) {
        double s = b[i];
        for (int k = outer[i]; k < diag[i]; ++k) s -= v[k] * x[inner[k]];
        x[i] = s / v[diag[i]];
    }
}

// One Gauss-Seidel sweep for A x = b, rows in increasing (forward) or decreasing order.
void gauss_seidel(const RowMajor& A, const std::vector<int>& diag, const double* b, double* x, bool forward) {
    const int* outer = A.outerIndexPtr();
    const int* inner = A.innerIndexPtr();
    const double* v = A.valuePtr();
    const Eigen::Index n = A.rows();
    for (Eigen::Index t = 0; t < n; ++t) {
        const Eigen::Index i = forward ? t : n - 1 - t;
        double s = b[i];
        for (int k = outer[i]; k < outer[i + 1]; ++k) s -= v[k] * x[inner[k]];
        x[i] += s / v[diag[i]];
    }
}

// Kc += P^T Kf P (N: the element DOF count when fixed at compile time).
template <int N>
void galerkin_add(Eigen::MatrixXd& Kc, const Eigen::MatrixXd& P, const Eigen::MatrixXd& Kf) {
    using M = Eigen::Matrix<double, N, N>;
    const Eigen::Map<const M> p(P.data(), P.rows(), P.cols()), kf(Kf.data(), Kf.rows(), Kf.cols());
    Eigen::Map<M> kc(Kc.data(), Kc.rows(), Kc.cols());
    const M kp = kf * p;
    kc.noalias() += p.transpose() * kp;
}

}  // namespace

struct GridMultigrid::Impl {
    const Model& model;
    int d = 0;
    int sweeps = 1;
    std::vector<Level> levels;
    Eigen::VectorXd scale;
    Eigen::SparseMatrix<double> coarsest;  // lower triangle of the last level's A
    detail::Cholesky llt;

    explicit Impl(const Model& m) : model(m) {}
    void vcycle(std::size_t l, const double* b = nullptr);
};

GridMultigrid::GridMultigrid(const Model& model, const std::vector<int>& free_of, int n_free, int coarse_dofs, int sweeps)
    : impl_(std::make_unique<Impl>(model)) {
    auto& I = *impl_;
    if (!model.grid) throw InputError("multigrid solver: the design mesh is not a structured grid of quadrilaterals");
    const Grid& g = *model.grid;
    const int d = I.d = model.dofs_per_node;
    I.sweeps = sweeps;

    // Level 0: the model's own DOF.
    Level L0;
    L0.nx = g.nx, L0.ny = g.ny;
    L0.dof_of_point.assign(static_cast<std::size_t>(g.nx + 1) * (g.ny + 1), -1);
    for (int node = 0; node < model.node_count; ++node) L0.dof_of_point[g.lattice_of_node[node]] = node * d;
    L0.free_of = free_of;
    L0.n = n_free;
    L0.nd = model.dofs_per_element;
    L0.element_unknowns.resize(model.element_dofs.size());
    for (std::size_t k = 0; k < model.element_dofs.size(); ++k) L0.element_unknowns[k] = free_of[model.element_dofs[k]];
    I.levels.push_back(std::move(L0));

    // Lattice point (i, j) of every element-local DOF row of the level-0 elements.
    auto point_of = [&](std::size_t l, int e, int a) {
        const Level& L = I.levels[l];
        if (l == 0) {
            const int node = model.element_dofs[static_cast<std::size_t>(e) * L.nd + a * d] / d;
            const int k = g.lattice_of_node[node];
            return std::pair{k % (L.nx + 1), k / (L.nx + 1)};
        }
        const int i = e % L.nx, j = e / L.nx;
        static constexpr int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
        return std::pair{i + di[a], j + dj[a]};
    };
    auto cell_of = [&](std::size_t l, int e) { return l == 0 ? g.cell_of_element[e] : e; };

    while (I.levels.back().n > coarse_dofs && (I.levels.back().nx > 1 || I.levels.back().ny > 1)) {
        const std::size_t l = I.levels.size() - 1;
        Level& F = I.levels[l];
        Level C;
        C.nx = coarse_cells(F.nx), C.ny = coarse_cells(F.ny);
        C.nd = 4 * d;
        const int cpoints = (C.nx + 1) * (C.ny + 1);
        C.dof_of_point.resize(cpoints);
        C.free_of.assign(static_cast<std::size_t>(cpoints) * d, -1);
        for (int J = 0; J <= C.ny; ++J)
            for (int Ic = 0; Ic <= C.nx; ++Ic) {
                const int p = J * (C.nx + 1) + Ic;
                C.dof_of_point[p] = p * d;
                const int fp = fine_line(J, F.ny) * (F.nx + 1) + fine_line(Ic, F.nx);
                for (int c = 0; c < d; ++c)  // supported where the fine node is
                    if (F.free_of[F.dof_of_point[fp] + c] >= 0) C.free_of[p * d + c] = C.n++;
            }
        const int ncells = C.nx * C.ny;
        C.element_unknowns.resize(static_cast<std::size_t>(ncells) * C.nd);
        for (int e = 0; e < ncells; ++e) {
            const int i = e % C.nx, j = e / C.nx;
            const int corner[4] = {j * (C.nx + 1) + i, j * (C.nx + 1) + i + 1, (j + 1) * (C.nx + 1) + i + 1,
                                   (j + 1) * (C.nx + 1) + i};
            for (int q = 0; q < 4; ++q)
                for (int c = 0; c < d; ++c) C.element_unknowns[static_cast<std::size_t>(e) * C.nd + q * d + c] = C.free_of[corner[q] * d + c];
        }
        C.K.assign(ncells, Eigen::MatrixXd::Zero(C.nd, C.nd));

        // Children and their transfer matrices (deduplicated: on a uniform grid a handful).
        C.children.assign(ncells, {{{-1, -1}, {-1, -1}, {-1, -1}, {-1, -1}}});
        std::map<std::pair<int, std::vector<double>>, int> known;
        const int nfine = static_cast<int>(F.element_unknowns.size() / F.nd);
        for (int e = 0; e < nfine; ++e) {
            const int cell = cell_of(l, e), fi = cell % F.nx, fj = cell / F.nx;
            const int Ic = std::min(fi / 2, C.nx - 1), Jc = std::min(fj / 2, C.ny - 1);
            const int X0 = fine_line(Ic, F.nx), X1 = fine_line(Ic + 1, F.nx);
            const int Y0 = fine_line(Jc, F.ny), Y1 = fine_line(Jc + 1, F.ny);
            Eigen::MatrixXd Pc = Eigen::MatrixXd::Zero(F.nd, C.nd);
            for (int a = 0; a < F.nd / d; ++a) {
                const auto [pi, pj] = point_of(l, e, a);
                const double tx = double(pi - X0) / (X1 - X0), ty = double(pj - Y0) / (Y1 - Y0);
                const double w[4] = {(1 - tx) * (1 - ty), tx * (1 - ty), tx * ty, (1 - tx) * ty};
                for (int c = 0; c < d; ++c) {
                    if (F.element_unknowns[static_cast<std::size_t>(e) * F.nd + a * d + c] < 0) continue;  // supported
                    for (int q = 0; q < 4; ++q) Pc(a * d + c, q * d + c) = w[q];
                }
            }
            const int id = l == 0 ? model.stiffness_of[e] : -1;
            auto [it, inserted] = known.try_emplace({id, std::vector<double>(Pc.data(), Pc.data() + Pc.size())},
                                                    static_cast<int>(C.transfer.size()));
            if (inserted) C.transfer.push_back(l == 0 ? Eigen::MatrixXd(Pc.transpose() * model.unique_stiffness[id] * Pc) : Pc);
            const int ce = Jc * C.nx + Ic;
            auto& slots = C.children[ce];
            for (auto& s : slots)
                if (s.first < 0) { s = {e, it->second}; break; }
        }

        // Prolongation P (fine unknowns x coarse unknowns) and restriction R = P^T.
        std::vector<Eigen::Triplet<double>> t;
        for (int pj = 0; pj <= F.ny; ++pj)
            for (int pi = 0; pi <= F.nx; ++pi) {
                const int fp = pj * (F.nx + 1) + pi;
                for (const auto& [Ix, wx] : line_weights(pi, F.nx))
                    for (const auto& [Jy, wy] : line_weights(pj, F.ny)) {
                        if (Ix < 0 || Jy < 0) continue;
                        const int cp = Jy * (C.nx + 1) + Ix;
                        for (int c = 0; c < d; ++c) {
                            const int r = F.free_of[F.dof_of_point[fp] + c], col = C.free_of[cp * d + c];
                            if (r >= 0 && col >= 0) t.emplace_back(r, col, wx * wy);
                        }
                    }
            }
        F.P.resize(F.n, C.n);
        F.P.setFromTriplets(t.begin(), t.end());
        F.R = F.P.transpose();
        I.levels.push_back(std::move(C));
    }

    for (auto& L : I.levels) {
        detail::build_pattern(L.n, L.nd, L.element_unknowns, /*lower_only=*/false, L.A, L.slot);
        L.diag.resize(L.n);
        for (int i = 0; i < L.n; ++i) {
            const int* begin = L.A.innerIndexPtr() + L.A.outerIndexPtr()[i];
            const int* end = L.A.innerIndexPtr() + L.A.outerIndexPtr()[i + 1];
            L.diag[i] = static_cast<int>(std::lower_bound(begin, end, i) - L.A.innerIndexPtr());
        }
        L.x.setZero(L.n), L.b.setZero(L.n), L.r.setZero(L.n);
    }
    I.coarsest = I.levels.back().A.triangularView<Eigen::Lower>();
    I.llt.analyzePattern(I.coarsest);
}

GridMultigrid::~GridMultigrid() = default;
int GridMultigrid::levels() const { return static_cast<int>(impl_->levels.size()); }
int GridMultigrid::coarsest_unknowns() const { return impl_->levels.back().n; }
const Eigen::SparseMatrix<double, Eigen::RowMajor>& GridMultigrid::level_operator(int level) const {
    return impl_->levels.at(level).A;
}
const Eigen::SparseMatrix<double, Eigen::RowMajor>& GridMultigrid::prolongation(int level) const {
    return impl_->levels.at(level).P;
}

bool GridMultigrid::set_scale(const Eigen::VectorXd& scale) {
    auto& I = *impl_;
    I.scale = scale;
    // Level 0: s_e K0_e.
    fill(I.levels[0], [&](std::size_t e) { return std::pair{scale(e), I.model.stiffness(static_cast<int>(e)).data()}; });
    // Coarse levels: Galerkin, cell by cell.
    for (std::size_t l = 1; l < I.levels.size(); ++l) {
        Level& C = I.levels[l];
        const Level& F = I.levels[l - 1];
        for (std::size_t ce = 0; ce < C.children.size(); ++ce) {
            Eigen::MatrixXd& Kc = C.K[ce];
            Kc.setZero();
            for (const auto& [child, tr] : C.children[ce]) {
                if (child < 0) continue;
                if (l == 1) Kc.noalias() += scale(child) * C.transfer[tr];
                else if (C.nd == 8) galerkin_add<8>(Kc, C.transfer[tr], F.K[child]);  // plane: fixed size, fast
                else galerkin_add<Eigen::Dynamic>(Kc, C.transfer[tr], F.K[child]);
            }
        }
        fill(C, [&](std::size_t e) { return std::pair{1.0, C.K[e].data()}; });
    }
    I.coarsest = I.levels.back().A.triangularView<Eigen::Lower>();
    return detail::factorize_regular(I.llt, I.coarsest);
}

// One V-cycle for A_l x = b (b: the level's right-hand side, L.b unless given); result in L.x.
void GridMultigrid::Impl::vcycle(std::size_t l, const double* b) {
    Level& L = levels[l];
    if (!b) b = L.b.data();
    if (l + 1 == levels.size()) {
        L.x = llt.solve(Eigen::Map<const Eigen::VectorXd>(b, L.n));
        return;
    }
    gauss_seidel_from_zero(L.A, L.diag, b, L.x.data());
    for (int s = 1; s < sweeps; ++s) gauss_seidel(L.A, L.diag, b, L.x.data(), true);
    csr_residual(L.A, L.x.data(), b, L.r.data());
    Level& C = levels[l + 1];
    csr_multiply(L.R, L.r.data(), C.b.data());
    vcycle(l + 1);
    csr_multiply_add(L.P, C.x.data(), L.x.data());
    for (int s = 0; s < sweeps; ++s) gauss_seidel(L.A, L.diag, b, L.x.data(), false);
}

Eigen::VectorXd GridMultigrid::multiply(const Eigen::VectorXd& x) const {
    Eigen::VectorXd y(x.size());
    csr_multiply(impl_->levels[0].A, x.data(), y.data());
    return y;
}

int GridMultigrid::solve(const Eigen::VectorXd& f, Eigen::VectorXd& u, double tolerance, int max_iterations) {
    auto& I = *impl_;
    Level& L = I.levels[0];
    const double fnorm = f.norm();
    if (u.size() != f.size()) u.setZero(f.size());
    if (fnorm == 0) {
        u.setZero();
        return 0;
    }
    Eigen::VectorXd r(f.size()), p(f.size()), q(f.size());
    const Eigen::VectorXd& z = L.x;  // the preconditioned residual, written by vcycle(0)
    const Eigen::Index n = f.size();
    const double limit = tolerance * fnorm;
    int it = 0;
    // The recursively updated residual drifts from f - K u by round-off (the stiffness contrast is
    // 1e9): CG stops on it, then restarts from the true residual until that one is small too.
    while (true) {
        csr_residual(L.A, u.data(), f.data(), r.data());
        if (r.norm() <= limit) return it;
        if (it >= max_iterations) break;
        I.vcycle(0, r.data());
        p = z;
        double rz = r.dot(z);
        while (it < max_iterations) {
            ++it;
            csr_multiply(L.A, p.data(), q.data());
            const double alpha = rz / p.dot(q);
            double rr = 0;
            for (Eigen::Index i = 0; i < n; ++i) {  // u += alpha p, r -= alpha q, |r|^2 in one pass
                u[i] += alpha * p[i];
                r[i] -= alpha * q[i];
                rr += r[i] * r[i];
            }
            if (std::sqrt(rr) <= limit) break;
            I.vcycle(0, r.data());
            const double rz_new = r.dot(z), beta = rz_new / rz;
            for (Eigen::Index i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
            rz = rz_new;
        }
    }
    throw SolverError(fmt::format("multigrid-CG: no convergence to {:g} after {} iterations (residual {:.3g} of |f|)",
                                  tolerance, max_iterations, r.norm() / fnorm));
}

}  // namespace fem::topopt
