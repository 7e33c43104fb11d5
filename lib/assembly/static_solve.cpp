#include "assembly/static_solve.hpp"

#include <Eigen/SparseCholesky>
#include <fmt/format.h>

#include "core/error.hpp"

namespace fem {

std::vector<Vec3> solve_linear_static(const AssembledSystem& sys, const std::vector<Vec3>& force) {
    const int nodes = sys.dofs.node_count();
    if (static_cast<int>(force.size()) != nodes)
        throw InputError(fmt::format("solve_linear_static: {} nodal forces for a mesh of {} nodes", force.size(), nodes));
    Eigen::VectorXd f = Eigen::VectorXd::Zero(sys.size());
    for (int n = 0; n < nodes; ++n)
        for (int c = 0; c < 3; ++c)
            if (const int d = sys.dofs.dof(n, c); d >= 0)
                if (const int r = sys.reduction.reduced_of_full[d]; r >= 0) f(r) += force[n][c];
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt(sys.stiffness);
    if (ldlt.info() != Eigen::Success) throw SolverError("solve_linear_static: the stiffness matrix could not be factorized");
    const Eigen::VectorXd d = ldlt.vectorD();
    if (!(d.minCoeff() > 0.0))
        throw SolverError("solve_linear_static: the stiffness matrix is singular or indefinite (missing supports?)");
    const Eigen::VectorXd u = ldlt.solve(f);
    const std::vector<double> t = sys.translations(u);
    std::vector<Vec3> out(nodes);
    for (int n = 0; n < nodes; ++n) out[n] = Vec3(t[3 * n], t[3 * n + 1], t[3 * n + 2]);
    return out;
}

}  // namespace fem
