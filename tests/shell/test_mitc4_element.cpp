// MITC4 element-level properties: symmetry, rigid-body modes, objectivity, mass, bad input.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "core/eigen_instances.hpp"
#include "core/error.hpp"
#include "element/shell_mitc4.hpp"
#include "../test_materials.hpp"

using namespace fem;
using fem::test::kShellSteel;
using fem::shell::Mat24;

namespace {

// A distorted and warped element (the four corners are not coplanar).
const std::array<Vec3, 4> kWarped = {Vec3(0, 0, 0), Vec3(2.0, 0.1, 0.05), Vec3(2.2, 1.7, -0.08), Vec3(-0.1, 1.5, 0.1)};

// The six rigid-body motions on the element's DOF: three translations, three rotations about the
// origin (u = omega x x, theta = omega).
Eigen::Matrix<double, 24, 6> rigid_modes(const std::array<Vec3, 4>& x) {
    Eigen::Matrix<double, 24, 6> R = Eigen::Matrix<double, 24, 6>::Zero();
    for (int k = 0; k < 4; ++k)
        for (int a = 0; a < 3; ++a) {
            R(6 * k + a, a) = 1.0;
            const Vec3 w = Vec3::Unit(a);
            R.block<3, 1>(6 * k, 3 + a) = w.cross(x[k]);
            R.block<3, 1>(6 * k + 3, 3 + a) = w;
        }
    return R;
}
}  // namespace

TEST(Mitc4, StiffnessIsSymmetricAndPositiveSemiDefinite) {
    const auto m = shell::mitc4_matrices(kWarped, 0.05, kShellSteel);
    EXPECT_LT((m.stiffness - m.stiffness.transpose()).norm(), 1e-14 * m.stiffness.norm());
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Eigen::MatrixXd(m.stiffness));  // core/eigen_instances.hpp
    EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-10 * eig.eigenvalues().maxCoeff());
}

TEST(Mitc4, SixRigidBodyModesHaveZeroEnergyAndNoMore) {
    for (double t : {0.2, 0.05, 0.001}) {
        const auto m = shell::mitc4_matrices(kWarped, t, kShellSteel);
        const auto R = rigid_modes(kWarped);
        // K R = 0: every rigid motion is stress free (including the drilling penalty).
        EXPECT_LT((m.stiffness * R).norm(), 1e-10 * m.stiffness.norm() * R.norm()) << "t = " << t;
        // Exactly six zero eigenvalues: the seventh is a deformation mode with clear stiffness.
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Eigen::MatrixXd(m.stiffness));  // core/eigen_instances.hpp
        const double top = eig.eigenvalues()[23];
        EXPECT_LT(std::abs(eig.eigenvalues()[5]), 1e-12 * top) << "t = " << t;
        EXPECT_GT(eig.eigenvalues()[6], 1e-10 * top) << "t = " << t;
    }
}

TEST(Mitc4, FlatElementHasExactlySixZeroModesToo) {
    const std::array<Vec3, 4> flat = {Vec3(0, 0, 0), Vec3(1.0, 0.2, 0), Vec3(1.3, 1.1, 0), Vec3(0.1, 0.8, 0)};
    const auto m = shell::mitc4_matrices(flat, 0.01, kShellSteel);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Eigen::MatrixXd(m.stiffness));  // core/eigen_instances.hpp
    const double top = eig.eigenvalues()[23];
    EXPECT_LT(std::abs(eig.eigenvalues()[5]), 1e-12 * top);
    EXPECT_GT(eig.eigenvalues()[6], 1e-12 * top);  // drilling penalty removes the drilling zero modes
}

TEST(Mitc4, MatricesRotateWithTheElement) {
    // Objectivity: rotating the element rotates K and M: K(Qx) = T K(x) T^T with T = diag(Q, ..., Q).
    const Mat3 Q = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    std::array<Vec3, 4> xr;
    for (int k = 0; k < 4; ++k) xr[k] = Q * kWarped[k] + Vec3(5, -2, 1);
    const auto a = shell::mitc4_matrices(kWarped, 0.05, kShellSteel);
    const auto b = shell::mitc4_matrices(xr, 0.05, kShellSteel);
    Mat24 T = Mat24::Zero();
    for (int i = 0; i < 8; ++i) T.block<3, 3>(3 * i, 3 * i) = Q;
    EXPECT_LT((b.stiffness - T * a.stiffness * T.transpose()).norm(), 1e-10 * a.stiffness.norm());
    EXPECT_LT((b.consistent_mass - T * a.consistent_mass * T.transpose()).norm(), 1e-10 * a.consistent_mass.norm());
    EXPECT_LT((b.lumped_mass - T * a.lumped_mass * T.transpose()).norm(), 1e-10 * a.lumped_mass.norm());
}

TEST(Mitc4, MassAndRotaryInertiaOfARectangle) {
    // 0.3 x 0.2 rectangle centred at the origin, t = 0.01: mass rho t A, inertia about x of the rigid
    // rotation rho t (A b^2/12 + A t^2/12) (the second term is the rotary inertia rho t^3/12 A).
    const double a = 0.3, b = 0.2, t = 0.01, rho = kShellSteel.density, A = a * b;
    const std::array<Vec3, 4> x = {Vec3(-a / 2, -b / 2, 0), Vec3(a / 2, -b / 2, 0), Vec3(a / 2, b / 2, 0),
                                   Vec3(-a / 2, b / 2, 0)};
    const auto m = shell::mitc4_matrices(x, t, kShellSteel);
    EXPECT_NEAR(m.area, A, 1e-15);
    const auto R = rigid_modes(x);
    for (const Mat24* M : {&m.consistent_mass, &m.lumped_mass}) {
        EXPECT_NEAR(R.col(0).dot(*M * R.col(0)), rho * t * A, 1e-12 * rho * t * A);
        EXPECT_NEAR(R.col(2).dot(*M * R.col(2)), rho * t * A, 1e-12 * rho * t * A);
    }
    const double Ix = rho * t * A * (b * b + t * t) / 12;
    EXPECT_NEAR(R.col(3).dot(m.consistent_mass * R.col(3)), Ix, 1e-12 * Ix);
    // The lumped matrix puts the mass at the corners: rho t A (b/2)^2 + rho t^3/12 A.
    const double Ix_lumped = rho * t * A * (b * b / 4 + t * t / 12);
    EXPECT_NEAR(R.col(3).dot(m.lumped_mass * R.col(3)), Ix_lumped, 1e-12 * Ix_lumped);
    // Both mass matrices are positive definite (the drilling rotation carries rho t^3/12 A_k).
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Eigen::MatrixXd(m.consistent_mass));
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
    EXPECT_GT(m.lumped_mass.diagonal().minCoeff(), 0.0);
}

TEST(Mitc4, BadInputNamesTheProblem) {
    EXPECT_THROW(shell::mitc4_matrices(kWarped, 0.0, kShellSteel), InputError);
    EXPECT_THROW(shell::mitc4_matrices(kWarped, -1.0, kShellSteel), InputError);
    const std::array<Vec3, 4> repeated = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
    EXPECT_THROW(shell::mitc4_matrices(repeated, 0.01, kShellSteel), InputError);
    // Clockwise in one corner only: a non-convex (arrow-head) quadrilateral.
    const std::array<Vec3, 4> arrow = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0.5, 0.5, 0), Vec3(0, 2, 0)};
    try {
        shell::mitc4_matrices(arrow, 0.01, kShellSteel);
        FAIL() << "a non-convex element was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("MITC4"), std::string::npos);
    }
}
