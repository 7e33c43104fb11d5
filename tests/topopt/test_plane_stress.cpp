// Verification of the plane-stress Quad4 / Quad8 elements (element/plane_stress.hpp): rigid-body
// modes, the patch test on distorted meshes, and a cantilever against beam theory.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>

#include "core/eigen_instances.hpp"
#include "core/error.hpp"
#include "element/plane_stress.hpp"
#include "mesh/mesh.hpp"
#include "topopt/model.hpp"
#include "topopt/simp.hpp"

using namespace fem;

namespace {

// A distorted quadrilateral (convex) with straight edges; Quad8 mid-side nodes at edge midpoints.
std::vector<Vec3> distorted(ElementShape shape) {
    std::vector<Vec3> x = {Vec3(0.0, 0.0, 0), Vec3(2.0, 0.3, 0), Vec3(2.4, 1.9, 0), Vec3(-0.2, 1.4, 0)};
    if (shape == ElementShape::Quad8)
        for (int k = 0; k < 4; ++k) x.push_back(0.5 * (x[k] + x[(k + 1) % 4]));
    return x;
}

class PlaneElement : public ::testing::TestWithParam<ElementShape> {};

TEST_P(PlaneElement, HasExactlyThreeRigidBodyModes) {
    const auto shape = GetParam();
    const auto x = distorted(shape);
    const Eigen::MatrixXd K = plane::stiffness(shape, x, 200e9, 0.3, 0.01);
    // Translations x, y and the rotation about z give zero force (to round-off of |K|).
    const int n = static_cast<int>(x.size());
    Eigen::MatrixXd R(2 * n, 3);
    for (int k = 0; k < n; ++k) {
        R.row(2 * k) << 1, 0, -x[k].y();
        R.row(2 * k + 1) << 0, 1, x[k].x();
    }
    EXPECT_LT((K * R).norm(), 1e-10 * K.norm() * R.norm());
    // ... and every other mode has positive stiffness: exactly three zero eigenvalues (full
    // integration, no hourglass modes).
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K);
    const auto& ev = eig.eigenvalues();
    const double scale = ev.maxCoeff();
    int zero = 0;
    for (int i = 0; i < ev.size(); ++i) zero += std::abs(ev(i)) < 1e-10 * scale;
    EXPECT_EQ(zero, 3);
    EXPECT_GT(ev(3), 1e-6 * scale);
}

TEST_P(PlaneElement, StrainOfALinearFieldIsExactEverywhere) {
    const auto shape = GetParam();
    const auto x = distorted(shape);
    // u = a + G x with a constant gradient G: eps = (G00, G11, G01 + G10) at every point.
    Eigen::Matrix2d G;
    G << 1e-3, -4e-4, 7e-4, 2e-3;
    Eigen::VectorXd u(2 * x.size());
    for (std::size_t k = 0; k < x.size(); ++k) u.segment<2>(2 * k) = Eigen::Vector2d(0.1, -0.2) + G * x[k].head<2>();
    Eigen::MatrixXd B;
    for (double xi : {-0.9, 0.0, 0.77})
        for (double eta : {-0.6, 0.3, 1.0}) {
            plane::strain_displacement(shape, x, xi, eta, B);
            const Eigen::Vector3d eps = B * u;
            EXPECT_NEAR(eps(0), G(0, 0), 1e-14);
            EXPECT_NEAR(eps(1), G(1, 1), 1e-14);
            EXPECT_NEAR(eps(2), G(0, 1) + G(1, 0), 1e-14);
        }
}

TEST_P(PlaneElement, PassesThePatchTestOnADistortedMesh) {
    // 2 x 2 elements on [0, 2]^2 with the centre node moved off-centre (all edges straight): the
    // boundary nodes follow a linear field, the interior nodes are solved for and must follow it too.
    const auto shape = GetParam();
    Mesh mesh = rectangle_quads(2.0, 2.0, 2, 2, shape);
    const Vec3 moved(1.23, 0.81, 0.0), old(1.0, 1.0, 0.0);
    // Distort: move the centre node and keep Quad8 mid-side nodes on their straight edges.
    for (auto& p : mesh.nodes) {
        // Piecewise-bilinear map of each quarter keeps edges straight: map the centre point.
        const double sx = p.x() <= 1 ? p.x() : 2 - p.x(), sy = p.y() <= 1 ? p.y() : 2 - p.y();
        const double w = sx * sy;  // 1 at the centre, 0 on the outer boundary, bilinear per quarter
        p += w * (moved - old);
    }
    const auto& b = mesh.blocks.front();
    const int ndof = 2 * mesh.node_count();
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(ndof, ndof);
    for (int e = 0; e < b.size(); ++e) {
        const auto x = mesh.element_coordinates(0, e);
        const Eigen::MatrixXd ke = plane::stiffness(shape, x, 70e9, 0.33, 0.002);
        auto nodes = b.element(e);
        for (std::size_t i = 0; i < nodes.size(); ++i)
            for (std::size_t j = 0; j < nodes.size(); ++j) K.block<2, 2>(2 * nodes[i], 2 * nodes[j]) += ke.block<2, 2>(2 * i, 2 * j);
    }
    Eigen::Matrix2d G;
    G << 2e-3, 5e-4, -1e-3, -1.5e-3;
    auto exact = [&](const Vec3& p) { Eigen::Vector2d v = Eigen::Vector2d(1e-3, 2e-3) + G * p.head<2>(); return v; };
    const auto boundary = topopt::boundary_nodes(mesh);
    std::vector<char> on(mesh.node_count(), 0);
    for (int n : boundary) on[n] = 1;
    std::vector<int> freed, fixed;
    for (int n = 0; n < mesh.node_count(); ++n)
        for (int c = 0; c < 2; ++c) (on[n] ? fixed : freed).push_back(2 * n + c);
    ASSERT_FALSE(freed.empty());
    Eigen::VectorXd ub(fixed.size());
    for (std::size_t i = 0; i < fixed.size(); ++i) ub(i) = exact(mesh.nodes[fixed[i] / 2])(fixed[i] % 2);
    Eigen::MatrixXd Kff(freed.size(), freed.size()), Kfb(freed.size(), fixed.size());
    for (std::size_t i = 0; i < freed.size(); ++i) {
        for (std::size_t j = 0; j < freed.size(); ++j) Kff(i, j) = K(freed[i], freed[j]);
        for (std::size_t j = 0; j < fixed.size(); ++j) Kfb(i, j) = K(freed[i], fixed[j]);
    }
    const Eigen::VectorXd uf = Kff.ldlt().solve(-Kfb * ub);
    for (std::size_t i = 0; i < freed.size(); ++i)
        EXPECT_NEAR(uf(i), exact(mesh.nodes[freed[i] / 2])(freed[i] % 2), 1e-12) << "DOF " << freed[i];
}

INSTANTIATE_TEST_SUITE_P(Quads, PlaneElement, ::testing::Values(ElementShape::Quad4, ElementShape::Quad8),
                         [](const auto& info) { return std::string(to_string(info.param)); });

TEST(PlaneStress, Quad8CantileverMatchesTimoshenkoBeamTheory) {
    // L = 1 m, h = 0.1 m, t = 0.01 m, tip load P = 100 N (parabolic shear would be exact; a
    // uniform edge load is close at L/h = 10). Timoshenko: d = P L^3 / (3 E I) + P L / (k G A),
    // k = 5/6. The clamped end (all nodes fixed) stiffens a little: 1 % tolerance.
    const double L = 1.0, h = 0.1, t = 0.01, E = 200e9, nu = 0.3, P = 100.0;
    const Mesh mesh = rectangle_quads(L, h, 40, 4, ElementShape::Quad8);
    auto model = topopt::plane_stress_model(mesh, ElasticMaterial::make("steel", E, nu, 7800), t);
    EXPECT_EQ(model.unique_stiffness.size(), 1u);  // one K_e for the regular grid
    model.fix(mesh.node_sets.at("x0"), {0, 1}, "clamp");
    const auto& tip = mesh.node_sets.at("x1");
    // Consistent loads of a uniform traction on quad8 edges: 1/6, 4/6, 1/6 per element edge.
    for (int n : tip) {
        const double y = mesh.nodes[n].y() / (h / 8.0);  // 0..8 in half-element steps
        const int iy = static_cast<int>(std::lround(y));
        const double w = (iy == 0 || iy == 8) ? 1.0 / 6.0 : (iy % 2 == 1 ? 4.0 / 6.0 : 2.0 / 6.0);
        model.add_force(0, n, Vec3(0, -P * w / 4.0, 0));
    }
    topopt::StiffnessSolver solver(model);
    const auto& u = solver.solve(Eigen::VectorXd::Ones(model.element_count()));
    double tip_v = 0;
    for (int n : tip) tip_v += u[0](2 * n + 1) / tip.size();
    const double I = t * h * h * h / 12, A = t * h, Gs = E / (2 * (1 + nu));
    const double d = P * L * L * L / (3 * E * I) + P * L / (5.0 / 6.0 * Gs * A);
    EXPECT_NEAR(-tip_v / d, 1.0, 0.01);
}

TEST(PlaneStress, RejectsBadInput) {
    auto x = distorted(ElementShape::Quad4);
    EXPECT_THROW(plane::stiffness(ElementShape::Quad4, x, 1e9, 0.3, 0.0), InputError);
    EXPECT_THROW(plane::stiffness(ElementShape::Quad4, x, 1e9, 0.5, 1.0), InputError);
    EXPECT_THROW(plane::stiffness(ElementShape::Tri3, x, 1e9, 0.3, 1.0), InputError);
    std::swap(x[1], x[3]);  // clockwise: inverted
    EXPECT_THROW(plane::stiffness(ElementShape::Quad4, x, 1e9, 0.3, 1.0), InputError);
}

}  // namespace
