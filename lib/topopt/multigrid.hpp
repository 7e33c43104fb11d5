#pragma once
// Conjugate gradients preconditioned by geometric multigrid, for K(rho) u = f on a structured grid
// (Model::grid): the approach of large-scale topology optimization (Amir, Aage & Lazarov 2014;
// Aage, Andreassen & Lazarov 2015), written for one core.
//
//   levels      the grid is coarsened 2:1 in each direction (a last odd cell stays one cell wide)
//               until the operator has at most `coarse_dofs` unknowns;
//   transfer    P = bilinear interpolation on the lattice, per DOF component; rows of supported
//               fine DOF are zero, and a coarse DOF is supported where its fine node is;
//   operators   Galerkin, K_{l+1} = P^T K_l P, assembled cell by cell: a coarse cell's matrix is
//               sum_children P_c^T K_c P_c (exact, because a fine cell lies in one coarse cell and
//               the interpolation inside it uses that cell's corners only). On the first coarse
//               level P_c^T K0_e P_c is precomputed, so it costs sum_children s_e G_c;
//   smoother    symmetric Gauss-Seidel: `sweeps` forward sweeps before the coarse correction,
//               as many backward after (a symmetric V-cycle, so CG may use it);
//   coarsest    sparse Cholesky (topopt/sparse_assembly.hpp), refactorized per design.
//
// CG stops when |f - K u| <= tolerance |f|; u on entry is the starting guess (the optimizer passes
// the previous design's displacement: the warm start).
#include <memory>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "topopt/model.hpp"

namespace fem::topopt {

class GridMultigrid {
public:
    /// `free_of`: model DOF -> unknown index (-1 when supported), `n_free` unknowns. Throws
    /// InputError when the model has no grid.
    GridMultigrid(const Model& model, const std::vector<int>& free_of, int n_free, int coarse_dofs = 4000,
                  int sweeps = 1);
    ~GridMultigrid();
    GridMultigrid(const GridMultigrid&) = delete;
    GridMultigrid& operator=(const GridMultigrid&) = delete;

    /// Assembles the fine operator with element stiffness scale s_e, the Galerkin operators of the
    /// coarse levels, and factorizes the coarsest. Returns false when that factorization fails or
    /// is numerically singular (supports that leave a rigid-body motion free).
    bool set_scale(const Eigen::VectorXd& scale);
    /// Preconditioned CG for the operator of the last set_scale(). Returns the iteration count;
    /// throws SolverError when it has not converged after max_iterations.
    int solve(const Eigen::VectorXd& f, Eigen::VectorXd& u, double tolerance, int max_iterations = 1000);

    /// y = K x with the fine operator (for tests).
    Eigen::VectorXd multiply(const Eigen::VectorXd& x) const;
    int levels() const;
    /// The operator of a level (0 = fine; both triangles) and the prolongation from level + 1 to it,
    /// for tests: operator(l + 1) must equal P^T operator(l) P.
    const Eigen::SparseMatrix<double, Eigen::RowMajor>& level_operator(int level) const;
    const Eigen::SparseMatrix<double, Eigen::RowMajor>& prolongation(int level) const;
    int coarsest_unknowns() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace fem::topopt
