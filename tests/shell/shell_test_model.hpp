#pragma once
// A small dense assembly of MITC4 shells, for the element's verification tests only (the library's
// sparse assembly lives in lib/assembly/). 6 DOF per node: ux uy uz rx ry rz, DOF = 6 node + d.
#include <array>
#include <vector>

#include <Eigen/Dense>

#include "core/eigen_instances.hpp"
#include "element/shell_mitc4.hpp"

namespace shelltest {

using fem::Vec3;

struct DenseShellModel {
    std::vector<Vec3> nodes;
    std::vector<std::array<int, 4>> quads;
    Eigen::MatrixXd K, M;  // assembled stiffness and mass

    int dofs() const { return 6 * static_cast<int>(nodes.size()); }

    void assemble(double thickness, const fem::ElasticMaterial& mat, bool lumped = false,
                  const fem::shell::Mitc4Options& opt = {}) {
        const int n = dofs();
        K = Eigen::MatrixXd::Zero(n, n);
        M = Eigen::MatrixXd::Zero(n, n);
        for (const auto& q : quads) {
            const std::array<Vec3, 4> x{nodes[q[0]], nodes[q[1]], nodes[q[2]], nodes[q[3]]};
            const auto em = fem::shell::mitc4_matrices(x, thickness, mat, opt);
            const auto& Me = lumped ? em.lumped_mass : em.consistent_mass;
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b) {
                    K.block<6, 6>(6 * q[a], 6 * q[b]) += em.stiffness.block<6, 6>(6 * a, 6 * b);
                    M.block<6, 6>(6 * q[a], 6 * q[b]) += Me.block<6, 6>(6 * a, 6 * b);
                }
        }
    }
};

/// Splits the DOF into fixed (flag true) and free ones.
struct Partition {
    std::vector<int> free, fixed;
    explicit Partition(const std::vector<bool>& is_fixed) {
        for (int i = 0; i < static_cast<int>(is_fixed.size()); ++i) (is_fixed[i] ? fixed : free).push_back(i);
    }
};

inline Eigen::MatrixXd sub(const Eigen::MatrixXd& A, const std::vector<int>& r, const std::vector<int>& c) {
    Eigen::MatrixXd S(r.size(), c.size());
    for (std::size_t i = 0; i < r.size(); ++i)
        for (std::size_t j = 0; j < c.size(); ++j) S(i, j) = A(r[i], c[j]);
    return S;
}

/// Static solve K u = f with u prescribed (u_fixed) on the fixed DOF; returns the full u.
inline Eigen::VectorXd solve_static(const Eigen::MatrixXd& K, const Eigen::VectorXd& f, const Partition& p,
                                    const Eigen::VectorXd& u_prescribed) {
    Eigen::VectorXd uc(p.fixed.size()), ff(p.free.size());
    for (std::size_t i = 0; i < p.fixed.size(); ++i) uc[i] = u_prescribed[p.fixed[i]];
    for (std::size_t i = 0; i < p.free.size(); ++i) ff[i] = f[p.free[i]];
    const Eigen::MatrixXd Kff = sub(K, p.free, p.free), Kfc = sub(K, p.free, p.fixed);
    const Eigen::VectorXd uf = Kff.ldlt().solve(ff - Kfc * uc);
    Eigen::VectorXd u = u_prescribed;
    for (std::size_t i = 0; i < p.free.size(); ++i) u[p.free[i]] = uf[i];
    return u;
}

/// Lowest natural frequencies (rad/s) with the fixed DOF held at zero.
inline Eigen::VectorXd natural_frequencies(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const Partition& p,
                                           int count) {
    const Eigen::MatrixXd Kff = sub(K, p.free, p.free), Mff = sub(M, p.free, p.free);
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(Kff, Mff, Eigen::EigenvaluesOnly);
    Eigen::VectorXd w(count);
    for (int i = 0; i < count; ++i) w[i] = std::sqrt(std::max(0.0, eig.eigenvalues()[i]));
    return w;
}

/// A structured nx x ny grid of quads on [0,lx] x [0,ly] (z = 0), node (i, j) = j (nx+1) + i.
inline DenseShellModel grid(double lx, double ly, int nx, int ny) {
    DenseShellModel m;
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) m.nodes.emplace_back(lx * i / nx, ly * j / ny, 0.0);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const int a = j * (nx + 1) + i;
            m.quads.push_back({a, a + 1, a + nx + 2, a + nx + 1});
        }
    return m;
}

}  // namespace shelltest
