#pragma once
// Mesh-independency filters of SIMP topology optimization (Sigmund 1997/2001; Bruns & Tortorelli
// 2001). Both use the linear "hat" weight H_ij = max(0, r - |c_i - c_j|) between element centroids
// c, times the neighbour's volume v_j, normalized so that every row sums to one:
//
//   W_ij = H_ij v_j / sum_k H_ik v_k          (a partition of unity: W 1 = 1)
//
//   density filter:      rho_phys = W x,   dc/dx = W^T dc/drho_phys,   dV/dx = W^T v
//   sensitivity filter:  dc~_i = v_i / max(gamma, x_i) * sum_j W_ij x_j dc_j / v_j   (gamma = 1e-3)
//
// For equal element volumes the sensitivity filter is Sigmund's classic heuristic. W is built once
// (a bucket search finds the neighbours within r) and stored as a sparse row-major matrix.
#include <span>
#include <vector>

#include <Eigen/Sparse>

#include "core/types.hpp"

namespace fem::topopt {

enum class FilterKind { None, Sensitivity, Density };

class Filter {
public:
    /// Builds W for elements with the given centroids and volumes and radius r (> 0; r smaller
    /// than the element spacing gives the identity). Throws InputError for r <= 0 or a size mismatch.
    Filter(std::span<const Vec3> centroids, std::span<const double> volumes, double radius);

    /// Memory W will need (bytes, an upper estimate): the constructor refuses a radius whose filter
    /// the machine cannot hold (fem::require_memory); readers can ask first to name the setting.
    static double estimated_bytes(std::span<const Vec3> centroids, double radius);

    const Eigen::SparseMatrix<double, Eigen::RowMajor>& weights() const { return W_; }
    double radius() const { return radius_; }

    /// rho_phys = W x.
    Eigen::VectorXd densities(const Eigen::VectorXd& x) const { return W_ * x; }
    /// Chain rule of the density filter: W^T g.
    Eigen::VectorXd backward(const Eigen::VectorXd& g) const { return W_.transpose() * g; }
    /// Sensitivity filter of dc at design x (see header comment).
    Eigen::VectorXd sensitivities(const Eigen::VectorXd& x, const Eigen::VectorXd& dc) const;

private:
    Eigen::SparseMatrix<double, Eigen::RowMajor> W_;
    Eigen::VectorXd volume_;
    double radius_;
};

}  // namespace fem::topopt
