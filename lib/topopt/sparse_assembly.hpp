#pragma once
// Internal to lib/topopt: the linear-algebra pieces the direct and the multigrid stiffness solvers
// share. The sparse pattern of an element-assembled matrix is built once, with the map from every
// element entry to its place in the value array, so that each design iteration only refills values.
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/SparseCholesky>
#ifdef FEM_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif
#ifdef _OPENMP
#include <omp.h>
#endif

namespace fem::topopt::detail {

#ifdef FEM_HAVE_CHOLMOD
using Cholesky = Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>;
inline constexpr const char* kCholesky = "CHOLMOD supernodal LLT";
#else
using Cholesky = Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>;
inline constexpr const char* kCholesky = "Eigen SimplicialLLT (AMD)";
#endif

// Debian's CHOLMOD 3 runs parts of the supernodal factorization with a compiled-in team of 4 OpenMP
// threads, and Eigen parallelizes row-major sparse products above 20,000 non-zeros. On a small
// shared machine (2 cores here, several jobs) that oversubscribes the cores and the threads spend
// their time spinning: measured 2-3x slower than one thread (and, through the density filter's
// products inside the OC bisection, 4x slower iterations). So the optimizer runs serially: this
// guard makes OpenMP regions inactive while it lives and restores the caller's setting afterwards.
struct SerialOpenMP {
#ifdef _OPENMP
    int saved = omp_get_max_active_levels();
    SerialOpenMP() { omp_set_max_active_levels(0); }
    ~SerialOpenMP() { omp_set_max_active_levels(saved); }
#endif
};

/// Pattern of the n x n matrix assembled from elements with `nd` unknowns each (element_unknowns:
/// nd per element, -1 for a supported DOF), either its lower triangle (column-major, for Cholesky)
/// or both triangles; and slot[(e nd + b) nd + a] = the value index of element entry (row a, column
/// b), -1 when none (supported DOF, or the upper triangle of a lower-only pattern).
template <class Sparse>
void build_pattern(int n, int nd, const std::vector<int>& element_unknowns, bool lower_only, Sparse& A,
                   std::vector<int>& slot) {
    const std::size_t ne = element_unknowns.size() / nd;
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(ne * nd * nd);
    for (std::size_t e = 0; e < ne; ++e)
        for (int a = 0; a < nd; ++a)
            for (int b = 0; b < nd; ++b) {
                const int r = element_unknowns[e * nd + a], c = element_unknowns[e * nd + b];
                if (r >= 0 && c >= 0 && (!lower_only || r >= c)) t.emplace_back(r, c, 1.0);
            }
    A.resize(n, n);
    A.setFromTriplets(t.begin(), t.end());
    A.makeCompressed();
    slot.assign(ne * nd * nd, -1);
    const int* outer = A.outerIndexPtr();
    const int* inner = A.innerIndexPtr();
    constexpr bool row_major = Sparse::IsRowMajor;
    for (std::size_t e = 0; e < ne; ++e)
        for (int b = 0; b < nd; ++b)
            for (int a = 0; a < nd; ++a) {
                const int r = element_unknowns[e * nd + a], c = element_unknowns[e * nd + b];
                if (r < 0 || c < 0 || (lower_only && r < c)) continue;
                const int o = row_major ? r : c, i = row_major ? c : r;
                const int* pos = std::lower_bound(inner + outer[o], inner + outer[o + 1], i);
                slot[(e * nd + b) * nd + a] = static_cast<int>(pos - inner);
            }
}

/// Factorizes K (lower triangle) and tells whether it is regular. With a rigid-body motion left free
/// (or a part of the mesh hanging loose) K is singular, and the Cholesky factorization either fails
/// or has a round-off pivot that makes the response to a generic load astronomically large. A
/// regular FE stiffness has |u| |K|_max / |f| of the order of its condition number (< 1e10 for any
/// reasonable mesh); a singular one gives ~1e15 and more.
inline bool factorize_regular(Cholesky& llt, const Eigen::SparseMatrix<double>& K) {
    llt.factorize(K);
    if (llt.info() != Eigen::Success) return false;
    Eigen::VectorXd f(K.rows());
    for (Eigen::Index i = 0; i < f.size(); ++i) f(i) = 1.0 + 0.5 * std::sin(1.7 * i);  // generic, deterministic
    const Eigen::VectorXd u = llt.solve(f);
    const double ratio = u.norm() * K.coeffs().cwiseAbs().maxCoeff() / f.norm();
    return std::isfinite(ratio) && ratio < 1e13;
}

}  // namespace fem::topopt::detail
