// Element-level checks of the linear solids (lib/element/solid_elements): rigid-body modes, mass,
// constant-strain patch behaviour and lumping, on undistorted and distorted elements.
#include <gtest/gtest.h>

#include <vector>

#include <Eigen/Eigenvalues>

#include "core/eigen_instances.hpp"
#include "core/error.hpp"
#include "element/solid_elements.hpp"
#include "mesh/mesh.hpp"
#include "../test_materials.hpp"

using namespace fem;
using fem::test::kSteel;

namespace {


// A distorted hex: the unit cube with corners moved (still convex).
std::vector<Vec3> distorted_hex() {
    return {Vec3(0, 0, 0), Vec3(1.1, 0.05, 0), Vec3(1.0, 0.9, 0.1), Vec3(-0.05, 1.0, 0),
            Vec3(0.1, 0, 1.0), Vec3(1.0, 0.1, 1.2), Vec3(1.1, 1.1, 0.9), Vec3(0, 0.95, 1.0)};
}

// A straight-edged tet10 with mid-edge nodes at the midpoints (Gmsh order).
std::vector<Vec3> tet10(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return {a, b, c, d, (a + b) / 2, (b + c) / 2, (a + c) / 2, (a + d) / 2, (c + d) / 2, (b + d) / 2};
}

// Number of eigenvalues below tol * largest.
int zero_modes(const Eigen::MatrixXd& K) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K);
    const double top = es.eigenvalues().maxCoeff();
    int z = 0;
    for (double l : es.eigenvalues()) z += std::abs(l) < 1e-10 * top;
    return z;
}

// Displacements of a linear field u = G x at the nodes, stacked ux, uy, uz per node.
Eigen::VectorXd linear_field(const std::vector<Vec3>& x, const Mat3& G) {
    Eigen::VectorXd u(3 * x.size());
    for (std::size_t a = 0; a < x.size(); ++a) u.segment<3>(3 * a) = G * x[a];
    return u;
}

}  // namespace

TEST(SolidElements, Hex8HasExactlySixRigidModesAndIsSymmetric) {
    for (bool im : {false, true}) {
        const Eigen::MatrixXd K = solid::hex8_stiffness(distorted_hex(), kSteel, im);
        EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
        EXPECT_EQ(zero_modes(K), 6) << "incompatible modes " << im;
    }
}

TEST(SolidElements, Tet10HasExactlySixRigidModes) {
    const auto x = tet10(Vec3(0, 0, 0), Vec3(1, 0.1, 0), Vec3(0.2, 1, 0), Vec3(0.1, 0.2, 1.3));
    EXPECT_EQ(zero_modes(solid::tet10_stiffness(x, kSteel)), 6);
}

TEST(SolidElements, ConstantStrainEnergyIsExact) {
    // Patch-test ingredient: for u = G x (constant strain eps), u^T K u = V eps:D:eps exactly, also on
    // a distorted hex with incompatible modes (Taylor's correction makes this hold).
    Mat3 G;
    G << 1e-3, 2e-4, -1e-4, 3e-4, -5e-4, 2e-4, 0.0, 1e-4, 7e-4;
    const Mat3 eps = 0.5 * (G + G.transpose());
    Eigen::Matrix<double, 6, 1> e;
    e << eps(0, 0), eps(1, 1), eps(2, 2), 2 * eps(0, 1), 2 * eps(1, 2), 2 * eps(2, 0);
    const double w = e.dot(solid::elasticity_matrix(kSteel) * e);
    const auto xh = distorted_hex();
    const double vh = solid::hex8_volume(xh);
    for (bool im : {false, true}) {
        const Eigen::VectorXd u = linear_field(xh, G);
        EXPECT_NEAR(u.dot(solid::hex8_stiffness(xh, kSteel, im) * u), vh * w, 1e-10 * vh * w) << "incompatible " << im;
    }
    const auto xt = tet10(Vec3(0, 0, 0), Vec3(1, 0.1, 0), Vec3(0.2, 1, 0), Vec3(0.1, 0.2, 1.3));
    const Eigen::VectorXd ut = linear_field(xt, G);
    const double vt = solid::tet10_volume(xt);
    EXPECT_NEAR(vt, (xt[1] - xt[0]).dot((xt[2] - xt[0]).cross(xt[3] - xt[0])) / 6, 1e-14);
    EXPECT_NEAR(ut.dot(solid::tet10_stiffness(xt, kSteel) * ut), vt * w, 1e-10 * vt * w);
}

TEST(SolidElements, MassesCarryTheElementMass) {
    const double rho = kSteel.density;
    const auto xh = distorted_hex();
    const double mh = rho * solid::hex8_volume(xh);
    // A rigid translation in x: u^T M u is the element mass, for every mass kind.
    Eigen::VectorXd tx = Eigen::VectorXd::Zero(24);
    for (int a = 0; a < 8; ++a) tx(3 * a) = 1;
    for (auto kind : {solid::MassKind::Consistent, solid::MassKind::Lumped})
        EXPECT_NEAR(tx.dot(solid::hex8_mass(xh, rho, kind) * tx), mh, 1e-12 * mh);

    const auto xt = tet10(Vec3(0, 0, 0), Vec3(1, 0.1, 0), Vec3(0.2, 1, 0), Vec3(0.1, 0.2, 1.3));
    const double mt = rho * solid::tet10_volume(xt);
    Eigen::VectorXd t10 = Eigen::VectorXd::Zero(30);
    for (int a = 0; a < 10; ++a) t10(3 * a + 1) = 1;
    for (auto rule : {solid::Tet10MassRule::Exact, solid::Tet10MassRule::FourPoint})
        EXPECT_NEAR(t10.dot(solid::tet10_mass(xt, rho, solid::MassKind::Consistent, rule) * t10), mt, 1e-12 * mt);
    // HRZ lumping: positive, corners 1/36 and mid-edge nodes 4/27 of the mass (straight tet).
    const Eigen::MatrixXd ml = solid::tet10_mass(xt, rho, solid::MassKind::Lumped);
    for (int a = 0; a < 4; ++a) EXPECT_NEAR(ml(3 * a, 3 * a), mt / 36, 1e-12 * mt);
    for (int a = 4; a < 10; ++a) EXPECT_NEAR(ml(3 * a, 3 * a), 4 * mt / 27, 1e-12 * mt);
    EXPECT_NEAR((ml - Eigen::MatrixXd(ml.diagonal().asDiagonal())).norm(), 0.0, 0.0);
}

TEST(SolidElements, Tet10ExactMassMatchesClosedForm) {
    // On a straight tet, int L1^a L2^b L3^c L4^d dV = 6V a! b! c! d! / (a+b+c+d+3)! gives
    // corner diagonal int (L(2L-1))^2 = 6V/420, mid-edge diagonal int (4 Li Lj)^2 = 32V/420 and
    // corner-corner int Li(2Li-1) Lj(2Lj-1) = V/420.
    const auto x = tet10(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 3));
    const double v = 1.0;
    const Eigen::MatrixXd m = solid::tet10_mass(x, 1.0);
    EXPECT_NEAR(m(0, 0), 6 * v / 420, 1e-14);
    EXPECT_NEAR(m(3 * 4, 3 * 4), 32 * v / 420, 1e-14);
    EXPECT_NEAR(m(0, 3), v / 420, 1e-14);  // corner 0 - corner 1
}

TEST(SolidElements, InvertedElementIsRefused) {
    auto x = distorted_hex();
    std::swap(x[4], x[0]), std::swap(x[5], x[1]), std::swap(x[6], x[2]), std::swap(x[7], x[3]);
    EXPECT_THROW(solid::hex8_stiffness(x, kSteel), InputError);
    EXPECT_THROW(solid::tet10_stiffness(tet10(Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)), kSteel), InputError);
    EXPECT_THROW(solid::hex8_mass(std::vector<Vec3>(5), 1.0), InputError);
}

namespace {
// A hex20 on the distorted hex's corners with straight edges (mid-edge nodes at the midpoints,
// ElementShape::Hex20 order), and its volume as the trilinear hex's.
std::vector<Vec3> distorted_hex20() {
    auto x = distorted_hex();
    static constexpr int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                         {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    for (const auto& e : edges) x.push_back((x[e[0]] + x[e[1]]) / 2);
    return x;
}
}  // namespace

// Hex20: six rigid-body modes with 3x3x3 Gauss; 2x2x2 (C3D20R) leaves six more zero-energy modes on a
// lone element (60 DOF, rank 8 points x 6 strains = 48). Constant strain energy exact with both rules,
// mass = rho V with both.
TEST(SolidElements, Hex20RigidModesConstantStrainAndMass) {
    const auto x = distorted_hex20();
    const Eigen::MatrixXd K = solid::hex20_stiffness(x, kSteel), Kr = solid::hex20_stiffness(x, kSteel, true);
    EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
    EXPECT_EQ(zero_modes(K), 6);
    EXPECT_EQ(zero_modes(Kr), 12);
    Mat3 G;
    G << 1e-3, 2e-4, -1e-4, 3e-4, -5e-4, 2e-4, 0.0, 1e-4, 7e-4;
    const Mat3 eps = 0.5 * (G + G.transpose());
    Eigen::Matrix<double, 6, 1> e;
    e << eps(0, 0), eps(1, 1), eps(2, 2), 2 * eps(0, 1), 2 * eps(1, 2), 2 * eps(2, 0);
    const double w = e.dot(solid::elasticity_matrix(kSteel) * e), v = solid::hex8_volume(distorted_hex());
    const Eigen::VectorXd u = linear_field(x, G);
    EXPECT_NEAR(u.dot(K * u), v * w, 1e-10 * v * w);
    EXPECT_NEAR(u.dot(Kr * u), v * w, 1e-10 * v * w);
    Eigen::VectorXd tz = Eigen::VectorXd::Zero(60);
    for (int a = 0; a < 20; ++a) tz(3 * a + 2) = 1;
    const double m = kSteel.density * v;
    for (bool reduced : {false, true})
        for (auto kind : {solid::MassKind::Consistent, solid::MassKind::Lumped})
            EXPECT_NEAR(tz.dot(solid::hex20_mass(x, kSteel.density, kind, reduced) * tz), m, 1e-12 * m);
    const Eigen::VectorXd lumped = solid::hex20_mass(x, kSteel.density, solid::MassKind::Lumped).diagonal();
    EXPECT_GT(lumped.minCoeff(), 0.0);
}

// The patch test on a mesh: a 2 x 2 x 2 box of hex20 with its inner corner node moved off the grid
// (and the mid-edge nodes around it on straight edges). Boundary nodes follow a linear field u = G x;
// solving K u = 0 for the inner nodes must give the same linear field there, with both rules.
TEST(SolidElements, Hex20PassesThePatchTest) {
    Mesh mesh = box_hex20(1.0, 1.0, 1.0, 2, 2, 2);
    const int centre = (1 * 3 + 1) * 3 + 1;  // box_hex8 numbering of corner (1, 1, 1)
    ASSERT_TRUE((mesh.nodes[centre] - Vec3(0.5, 0.5, 0.5)).norm() < 1e-12);
    mesh.nodes[centre] += Vec3(0.08, -0.05, 0.06);
    // Mid-edge nodes on the edges from the centre: back to their edges' midpoints.
    for (int e = 0; e < mesh.blocks[0].size(); ++e) {
        const auto c = mesh.blocks[0].element(e);
        static constexpr int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                             {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
        for (int k = 0; k < 12; ++k) mesh.nodes[c[8 + k]] = (mesh.nodes[c[edges[k][0]]] + mesh.nodes[c[edges[k][1]]]) / 2;
    }
    std::vector<bool> boundary(mesh.node_count(), false);
    for (const char* face : {"x0", "x1", "y0", "y1", "z0", "z1"})
        for (int n : mesh.node_set(face)) boundary[n] = true;
    Mat3 G;
    G << 1e-3, 2e-4, -1e-4, 3e-4, -5e-4, 2e-4, 0.0, 1e-4, 7e-4;
    const Eigen::VectorXd exact = linear_field(mesh.nodes, G);
    for (bool reduced : {false, true}) {
        const int n = 3 * mesh.node_count();
        Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
        for (int e = 0; e < mesh.blocks[0].size(); ++e) {
            const auto c = mesh.blocks[0].element(e);
            const Eigen::MatrixXd Ke = solid::hex20_stiffness(mesh.element_coordinates(0, e), kSteel, reduced);
            for (int a = 0; a < 20; ++a)
                for (int b = 0; b < 20; ++b) K.block<3, 3>(3 * c[a], 3 * c[b]) += Ke.block<3, 3>(3 * a, 3 * b);
        }
        std::vector<int> inner, outer;
        for (int i = 0; i < mesh.node_count(); ++i)
            for (int d = 0; d < 3; ++d) (boundary[i] ? outer : inner).push_back(3 * i + d);
        Eigen::MatrixXd Kii(inner.size(), inner.size()), Kio(inner.size(), outer.size());
        Eigen::VectorXd uo(outer.size()), ui_exact(inner.size());
        for (std::size_t a = 0; a < inner.size(); ++a) {
            ui_exact(a) = exact(inner[a]);
            for (std::size_t b = 0; b < inner.size(); ++b) Kii(a, b) = K(inner[a], inner[b]);
            for (std::size_t b = 0; b < outer.size(); ++b) Kio(a, b) = K(inner[a], outer[b]);
        }
        for (std::size_t b = 0; b < outer.size(); ++b) uo(b) = exact(outer[b]);
        const Eigen::VectorXd ui = Kii.ldlt().solve(-Kio * uo);
        EXPECT_LT((ui - ui_exact).norm(), 1e-9 * ui_exact.norm()) << "reduced " << reduced;
    }
}

// CalculiX's C3D8I (hex8_incompatible_dofs): the incompatible-modes brick with its nine bubble
// amplitudes kept as DOFs with mass.
TEST(SolidElements, Hex8IncompatibleDofsCondenseToTheIncompatibleBrick) {
    const auto x = distorted_hex();
    const solid::Hex8IncompatibleDofs e = solid::hex8_incompatible_dofs(x, kSteel);
    ASSERT_EQ(e.stiffness.rows(), 33);
    ASSERT_EQ(e.mass.rows(), 33);
    EXPECT_LT((e.stiffness - e.stiffness.transpose()).norm(), 1e-12 * e.stiffness.norm());
    EXPECT_LT((e.mass - e.mass.transpose()).norm(), 1e-12 * e.mass.norm());
    // Six rigid-body modes, none more: every bubble is strained.
    EXPECT_EQ(zero_modes(e.stiffness), 6);
    // Static condensation of the bubbles is the library's incompatible-modes brick.
    const Eigen::MatrixXd kuu = e.stiffness.topLeftCorner(24, 24), kua = e.stiffness.topRightCorner(24, 9);
    const Eigen::MatrixXd kaa = e.stiffness.bottomRightCorner(9, 9);
    const Eigen::MatrixXd condensed = kuu - kua * kaa.ldlt().solve(kua.transpose());
    const Eigen::MatrixXd brick = solid::hex8_stiffness(x, kSteel, true);
    EXPECT_LT((condensed - brick).norm(), 1e-12 * brick.norm());
    // And the nodal block is the trilinear brick's.
    EXPECT_LT((kuu - solid::hex8_stiffness(x, kSteel, false)).norm(), 1e-12 * kuu.norm());
}

TEST(SolidElements, Hex8IncompatibleDofsPassThePatchTest) {
    // Patch test (Taylor, Beresford & Wilson 1976): nodal values of a linear field u = G x leave the
    // bubbles unloaded (K_au u = 0, so they stay at zero) and carry the exact constant-strain energy,
    // on a distorted element.
    Mat3 G;
    G << 1e-3, 2e-4, -1e-4, 3e-4, -5e-4, 2e-4, 0.0, 1e-4, 7e-4;
    const auto x = distorted_hex();
    const solid::Hex8IncompatibleDofs e = solid::hex8_incompatible_dofs(x, kSteel);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(33);
    u.head(24) = linear_field(x, G);
    const Eigen::VectorXd f = e.stiffness * u;
    EXPECT_LT(f.tail(9).norm(), 1e-12 * f.head(24).norm());
    const Mat3 eps = 0.5 * (G + G.transpose());
    Eigen::Matrix<double, 6, 1> v;
    v << eps(0, 0), eps(1, 1), eps(2, 2), 2 * eps(0, 1), 2 * eps(1, 2), 2 * eps(2, 0);
    const double w = solid::hex8_volume(x) * v.dot(solid::elasticity_matrix(kSteel) * v);
    EXPECT_NEAR(u.dot(f), w, 1e-10 * w);
}

TEST(SolidElements, Hex8IncompatibleDofsMassIsCalculixs) {
    // Nodal block: the consistent trilinear mass. Bubbles: with the 2x2x2 rule each is 2/3 at every
    // point, so a bubble carries 4/9 of the element mass (parallelepiped; the exact integral would give
    // 8/15) and couples with a node by 2/3 of the node's consistent share, 1/12 of the mass.
    const std::vector<Vec3> box = {Vec3(0, 0, 0), Vec3(0.5, 0, 0), Vec3(0.5, 0.2, 0), Vec3(0, 0.2, 0),
                                   Vec3(0, 0, 0.3), Vec3(0.5, 0, 0.3), Vec3(0.5, 0.2, 0.3), Vec3(0, 0.2, 0.3)};
    const double mass = kSteel.density * 0.5 * 0.2 * 0.3;
    const solid::Hex8IncompatibleDofs e = solid::hex8_incompatible_dofs(box, kSteel);
    EXPECT_LT((e.mass.topLeftCorner(24, 24) - solid::hex8_mass(box, kSteel.density)).norm(), 1e-12 * mass);
    for (int k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d) {
            const int i = 24 + 3 * k + d;
            EXPECT_NEAR(e.mass(i, i), 4.0 / 9 * mass, 1e-12 * mass);
            for (int l = 0; l < 3; ++l) EXPECT_NEAR(e.mass(i, 24 + 3 * l + d), 4.0 / 9 * mass, 1e-12 * mass);
            for (int a = 0; a < 8; ++a) EXPECT_NEAR(e.mass(i, 3 * a + d), mass / 12, 1e-12 * mass);
            EXPECT_EQ(e.mass(i, 24 + 3 * k + (d + 1) % 3), 0.0);  // components do not couple
        }
}
