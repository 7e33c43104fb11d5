// DOF numbering, constraint reduction and sparse assembly (lib/assembly).
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "assembly/model.hpp"
#include "assembly/static_solve.hpp"
#include "core/error.hpp"
#include "../test_materials.hpp"

using namespace fem;
using fem::test::kSteel;

namespace {
// Full dense matrix from a stored lower triangle.
Eigen::MatrixXd dense(const Eigen::SparseMatrix<double>& lower) {
    return Eigen::MatrixXd(Eigen::SparseMatrix<double>(lower.selfadjointView<Eigen::Lower>()));
}
}

TEST(DofMap, MixesThreeAndSixDofNodes) {
    DofMap d(4);
    d.require(0, 3), d.require(1, 6), d.require(1, 3), d.require(2, 3), d.require(2, 6);
    d.finalize();
    EXPECT_EQ(d.size(), 15);  // node 3 untouched
    EXPECT_EQ(d.dof(0, UZ), 2);
    EXPECT_EQ(d.dof(0, RX), -1);
    EXPECT_EQ(d.dof(1, RZ), 8);
    EXPECT_EQ(d.dof(2, UX), 9);
    EXPECT_EQ(d.dofs(3), 0);
    EXPECT_THROW(d.require(9, 3), InputError);
    EXPECT_THROW(d.require(0, 4), InputError);
}

TEST(Constraints, CouplingChainsAndSupportsPropagate) {
    DofMap d(4);
    for (int n = 0; n < 4; ++n) d.require(n, 3);
    d.finalize();
    Constraints c;
    c.couple({0, 1}, dof_bit(UX));
    c.couple({1, 2}, dof_bit(UX));      // chain: 0-1-2 share ux
    c.couple({2, 3}, dof_bit(UY));
    c.fix(3, dof_bit(UY));              // ...and 2's uy is fixed through the coupling
    c.fix(0, dof_bit(RX));              // a rotation a solid node does not carry: skipped
    const auto r = c.reduce(d);
    EXPECT_EQ(r.reduced_of_full[d.dof(1, UX)], r.reduced_of_full[d.dof(0, UX)]);
    EXPECT_EQ(r.reduced_of_full[d.dof(2, UX)], r.reduced_of_full[d.dof(0, UX)]);
    EXPECT_EQ(r.reduced_of_full[d.dof(2, UY)], -1);
    EXPECT_EQ(r.reduced_of_full[d.dof(3, UY)], -1);
    EXPECT_EQ(r.fixed, 2);
    EXPECT_EQ(r.coupled, 2);
    EXPECT_EQ(r.size, 12 - 4);
    Constraints bad;
    bad.couple({0, 1}, dof_bit(RZ));
    EXPECT_THROW(bad.reduce(d), InputError);
}

TEST(Assembly, MatchesDenseAssemblyAndCarriesTheMass) {
    const Mesh mesh = box_hex8(0.3, 0.2, 0.1, 3, 2, 1);
    Model model(mesh);
    model.add_solid_part("box", kSteel);
    const AssembledSystem sys = model.assemble();
    ASSERT_EQ(sys.size(), 3 * mesh.node_count());
    // Dense reference assembly element by element.
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(sys.size(), sys.size());
    const auto& b = mesh.blocks[0];
    for (int e = 0; e < b.size(); ++e) {
        const Eigen::MatrixXd ke = solid::hex8_stiffness(mesh.element_coordinates(0, e), kSteel);
        const auto conn = b.element(e);
        for (int i = 0; i < 24; ++i)
            for (int j = 0; j < 24; ++j) K(3 * conn[i / 3] + i % 3, 3 * conn[j / 3] + j % 3) += ke(i, j);
    }
    const Eigen::MatrixXd Ks = dense(sys.stiffness);
    EXPECT_LT((Ks - K).norm(), 1e-12 * K.norm());
    // Rigid translation: u^T M u = rho V, K u = 0.
    Eigen::VectorXd u = Eigen::VectorXd::Zero(sys.size());
    for (int n = 0; n < mesh.node_count(); ++n) u(3 * n + 2) = 1;
    const Eigen::VectorXd mu = sys.mass.selfadjointView<Eigen::Lower>() * u;
    EXPECT_NEAR(u.dot(mu), 7800.0 * 0.3 * 0.2 * 0.1, 1e-9);
    EXPECT_LT((sys.stiffness.selfadjointView<Eigen::Lower>() * u).norm(), 1e-6 * K.norm());
}

TEST(Assembly, CouplingIsMasterSlaveElimination) {
    // Two boxes side by side with duplicate nodes at x = 0.1, coupled: K_red = T^T K T.
    Mesh mesh = box_hex8(0.1, 0.1, 0.1, 1, 1, 1, "a");
    Mesh right = box_hex8(0.1, 0.1, 0.1, 1, 1, 1, "b");
    right.translate(Vec3(0.1, 0, 0));
    const int offset = mesh.node_count();
    mesh.append(right);
    Model model(mesh);
    model.add_solid_part("a", kSteel);
    model.add_solid_part("b", kSteel);
    const Mesh one = box_hex8(0.1, 0.1, 0.1, 1, 1, 1);
    std::vector<int> a0 = one.node_set("x0"), a1 = one.node_set("x1"), b0;
    for (int n : one.node_set("x0")) b0.push_back(n + offset);
    EXPECT_EQ(model.couple_coincident(a1, b0), 4);
    model.fix_nodes(a0);
    const AssembledSystem sys = model.assemble();
    EXPECT_EQ(sys.size(), 3 * (16 - 4 - 4));  // 16 nodes, 4 slaves, 4 fixed
    EXPECT_EQ(sys.reduction.coupled, 12);

    // The same through an explicit 0/1 matrix T on the unconstrained system.
    Model free(mesh);
    free.add_solid_part("a", kSteel);
    free.add_solid_part("b", kSteel);
    const AssembledSystem full = free.assemble();
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(full.size(), sys.size());
    for (int i = 0; i < full.size(); ++i)
        if (sys.reduction.reduced_of_full[i] >= 0) T(i, sys.reduction.reduced_of_full[i]) = 1;
    const Eigen::MatrixXd Kf = dense(full.stiffness);
    const Eigen::MatrixXd Kr = dense(sys.stiffness);
    EXPECT_LT((T.transpose() * Kf * T - Kr).norm(), 1e-12 * Kf.norm());

    Model lonely(mesh);
    lonely.add_solid_part("a", kSteel);
    EXPECT_THROW(lonely.couple_coincident({0}, {1}), InputError);  // no partner at node 0's place
}

TEST(Assembly, SixDofBlocksPlugIn) {
    // A stand-in 6-DOF kernel (identity matrices) on a quad block shares nodes with nothing: each
    // node gets 6 DOFs and the assembled diagonal counts the elements at each node.
    const Mesh mesh = rectangle_quads(1.0, 1.0, 2, 1);
    Model model(mesh);
    model.add_block(0, 6, [](std::span<const Vec3>, int) {
        return ElementMatrices{Eigen::MatrixXd::Identity(24, 24), Eigen::MatrixXd::Identity(24, 24)};
    });
    const AssembledSystem sys = model.assemble();
    EXPECT_EQ(sys.size(), 6 * 6);
    EXPECT_EQ(sys.dofs.dof(1, RZ), 6 + 5);
    EXPECT_DOUBLE_EQ(sys.stiffness.coeff(sys.dofs.dof(1, RY), sys.dofs.dof(1, RY)), 2.0);  // middle node: 2 elements
    EXPECT_DOUBLE_EQ(sys.stiffness.coeff(sys.dofs.dof(0, RY), sys.dofs.dof(0, RY)), 1.0);
    EXPECT_THROW(Model(mesh).add_solid_part("plate", kSteel), InputError);  // no solid quad4
}

TEST(Assembly, ElementInternalDofsFollowTheNodalEquations) {
    // The incompatible-modes brick with its bubbles as element DOFs (CalculiX's C3D8I) on a clamped
    // 4 x 1 x 1 beam: the internal DOFs come after the nodal equations, each element's own, and a
    // static solve gives the same nodal displacements as the statically condensed brick.
    const Mesh mesh = box_hex8(0.4, 0.1, 0.1, 4, 1, 1, "beam");
    Model kept(mesh), condensed(mesh);
    kept.add_block(0, 3, [](std::span<const Vec3> x, int) {
        solid::Hex8IncompatibleDofs e = solid::hex8_incompatible_dofs(x, kSteel);
        return ElementMatrices{e.stiffness, e.mass};
    }, 9);
    condensed.add_solid_part("beam", kSteel);
    for (Model* m : {&kept, &condensed}) m->fix_node_set("x0");
    const AssembledSystem sk = kept.assemble(), sc = condensed.assemble();
    EXPECT_EQ(sk.reduction.size, sc.size());
    EXPECT_EQ(sk.internal_dofs, 4 * 9);
    EXPECT_EQ(sk.size(), sc.size() + 4 * 9);
    // Element 1's bubbles touch element 1's nodes only, never element 0's or 2's own DOFs.
    const Eigen::MatrixXd k = dense(sk.stiffness);
    const int first = sk.reduction.size + 9;
    EXPECT_NE(k(first, first), 0.0);
    EXPECT_EQ(k(first + 9, first), 0.0);
    EXPECT_EQ(k(first, first - 9), 0.0);
    std::vector<Vec3> force(mesh.node_count(), Vec3::Zero());
    for (int n : mesh.node_set("x1")) force[n] = Vec3(100.0, -200.0, 300.0);
    const std::vector<Vec3> uk = solve_linear_static(sk, force), uc = solve_linear_static(sc, force);
    double diff = 0, size = 0;
    for (int n = 0; n < mesh.node_count(); ++n) diff = std::max(diff, (uk[n] - uc[n]).norm()), size = std::max(size, uc[n].norm());
    EXPECT_LT(diff, 1e-10 * size);
    EXPECT_THROW(kept.add_block(0, 3, nullptr, -1), InputError);
}
