#pragma once
// Shared by the Belytschko-Tsay shell tests and the explicit bench: the linearized shell model as
// dense matrices (the kernel's exact linear stiffness assembled with the group's lumped masses), its
// highest frequency, and static solutions by dynamic relaxation on the explicit solver.
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <vector>

#include "core/eigen_instances.hpp"
#include "explicit/shell_group.hpp"
#include "explicit/solver.hpp"

namespace fem::test {

/// Dense linear stiffness K and lumped mass diagonal of one shell group (its block), 6 DOFs per
/// mesh node (ux uy uz rx ry rz), on the reference geometry.
struct DenseShellSystem {
    Eigen::MatrixXd K;
    Eigen::VectorXd mass;  // diagonal
};
inline DenseShellSystem dense_shell_system(const Mesh& mesh, const ShellGroup& g) {
    const int n = 6 * mesh.node_count();
    DenseShellSystem s{Eigen::MatrixXd::Zero(n, n), Eigen::VectorXd::Zero(n)};
    for (int e = 0; e < g.size(); ++e) {
        const auto& c = g.connectivity(e);
        const std::array<Vec3, 4> X{mesh.nodes[c[0]], mesh.nodes[c[1]], mesh.nodes[c[2]], mesh.nodes[c[3]]};
        const auto Ke = shellbt::linear_stiffness(g.constants(), X);
        for (int I = 0; I < 4; ++I)
            for (int J = 0; J < 4; ++J) s.K.block<6, 6>(6 * c[I], 6 * c[J]) += Ke.block<6, 6>(6 * I, 6 * J);
        const auto& lm = g.lumped_mass(e);
        for (int I = 0; I < 4; ++I)
            for (int d = 0; d < 6; ++d) s.mass[6 * c[I] + d] += d < 3 ? lm.mass[I] : lm.inertia[I];
    }
    return s;
}

/// Eigenvalues omega^2 of the free DOFs (fixed[i] true: held) of K against the diagonal mass.
inline Eigen::VectorXd dense_eigenvalues(const DenseShellSystem& s, const std::vector<bool>& fixed) {
    std::vector<int> free;
    for (int i = 0; i < static_cast<int>(fixed.size()); ++i)
        if (!fixed[i] && s.mass[i] > 0) free.push_back(i);
    const int n = static_cast<int>(free.size());
    Eigen::MatrixXd A(n, n);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
            A(a, b) = 0.5 * (s.K(free[a], free[b]) + s.K(free[b], free[a])) / std::sqrt(s.mass[free[a]] * s.mass[free[b]]);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A, Eigen::EigenvaluesOnly);
    return eig.eigenvalues();
}

/// The quad mesh (one block) with every quadrilateral split into two triangles along alternating
/// diagonals; nodes and node sets kept.
inline Mesh split_into_triangles(const Mesh& quads) {
    Mesh m;
    m.nodes = quads.nodes;
    m.node_sets = quads.node_sets;
    ElementBlock tri{quads.blocks[0].part, ElementShape::Tri3, {}};
    for (int e = 0; e < quads.blocks[0].size(); ++e) {
        const auto q = quads.blocks[0].element(e);
        const int a[3] = {q[0], q[1], q[2]}, b[3] = {q[0], q[2], q[3]};
        const int c[3] = {q[0], q[1], q[3]}, d[3] = {q[1], q[2], q[3]};
        tri.add(e % 2 == 0 ? a : c);
        tri.add(e % 2 == 0 ? b : d);
    }
    m.blocks.push_back(tri);
    return m;
}

}  // namespace fem::test
