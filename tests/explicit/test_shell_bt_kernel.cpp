// Element-level verification of the Belytschko-Tsay shell kernel (element/shell_bt_explicit.hpp):
// membrane and bending patch tests on a distorted patch placed obliquely in space, large rigid
// rotations of a prestressed element (corotational objectivity), the zero-energy modes of the
// stiffness (rigid body + drilling only, once hourglass control is on), degenerate triangles, and
// the rotational-inertia scaling against the Table 2-1 step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "core/eigen_instances.hpp"
#include "core/error.hpp"
#include "element/critical_time_step.hpp"
#include "element/shell_bt_explicit.hpp"
#include "explicit_test_support.hpp"

using namespace fem;
using namespace fem::test;
using namespace fem::shellbt;

namespace {


// The distorted five-element membrane patch of MacNeal and Harder (1985): a 0.24 x 0.12 rectangle
// with four interior nodes; nodes 0-3 the corners, 4-7 the interior ones.
struct Patch {
    std::vector<Vec3> nodes;
    std::vector<std::array<int, 4>> quads;
    std::vector<int> interior{4, 5, 6, 7};
};
Patch macneal_harder(const Mat3& Q, const Vec3& offset) {
    Patch p;
    const double xy[8][2] = {{0, 0}, {0.24, 0}, {0.24, 0.12}, {0, 0.12}, {0.04, 0.02}, {0.18, 0.03}, {0.16, 0.08}, {0.08, 0.08}};
    for (const auto& c : xy) p.nodes.push_back(offset + Q * Vec3(c[0], c[1], 0.0));
    p.quads = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}, {4, 5, 6, 7}};
    return p;
}

std::array<Vec3, 4> element_nodes(const std::vector<Vec3>& x, const std::array<int, 4>& q) {
    return {x[q[0]], x[q[1]], x[q[2]], x[q[3]]};
}

// The element's in-plane stress at point p as a global tensor (frame f).
Mat3 global_stress(const Frame& f, const State& s, int p) {
    Mat3 local = Mat3::Zero();
    local(0, 0) = s.sigma[p][0];
    local(1, 1) = s.sigma[p][1];
    local(0, 1) = local(1, 0) = s.sigma[p][2];
    return f.E * local * f.E.transpose();
}

// Plane-stress stress of an in-plane strain tensor (global, in the plane with unit normal n).
Mat3 plane_stress(const Mat3& eps, const Vec3& n, const ElasticMaterial& m) {
    const Mat3 P = Mat3::Identity() - n * n.transpose();
    const Mat3 e = P * eps * P;
    const double E = m.youngs_modulus, nu = m.poissons_ratio;
    return E / (1 + nu) * (e + nu / (1 - nu) * e.trace() * P);
}
}  // namespace

// Membrane patch test (small strain): on the reference frames, the increments of a linear
// displacement field u = H X (nodes turned by its skew part) must give every element the same
// stress C eps(H) at every point through the thickness, no hourglass or drilling resultant, and zero
// net force and moment at the four interior nodes (the forces of a constant stress balance). The
// patch lies in an oblique plane.
TEST(ShellBtKernel, MembranePatchTestOnDistortedObliquePatchIsExact) {
    const Mat3 Q = rotation(0.7, Vec3(1, -2, 0.5));
    const Vec3 n = Q.col(2);
    Patch p = macneal_harder(Q, Vec3(0.3, -0.1, 0.2));
    ShellSection sec{.thickness = 2e-3};
    const Constants c = Constants::from(kShellSteel, sec);
    Mat3 h2;  // in-plane gradient (local patch axes), unsymmetric: includes a small rotation
    h2 << 1.0e-3, 0.4e-3, 0, -0.1e-3, -0.5e-3, 0, 0, 0, 0;
    const Mat3 H = Q * h2 * Q.transpose();
    const Mat3 eps = 0.5 * (H + H.transpose());
    const Mat3 expected = plane_stress(eps, n, kShellSteel);
    std::vector<Vec3> f(p.nodes.size(), Vec3::Zero()), m(p.nodes.size(), Vec3::Zero());
    for (const auto& q : p.quads) {
        const auto X = element_nodes(p.nodes, q);
        const Frame fr = make_frame(X);
        // The nodes turn with the field's rotation (its skew part), as they would in a mesh.
        const Mat3 W = 0.5 * (H - H.transpose());
        std::array<Vec3, 4> du, dth;
        for (int a = 0; a < 4; ++a) {
            du[a] = H * X[a];
            dth[a] = Vec3(W(2, 1), W(0, 2), W(1, 0));
        }
        State s;
        update_state(c, fr, du, dth, s);
        for (double hq : s.hourglass)
            EXPECT_NEAR(hq, 0.0, 1e-12 * kShellSteel.youngs_modulus * sec.thickness * H.norm() * 0.24);
        for (double md : s.drilling)
            EXPECT_NEAR(md, 0.0, 1e-12 * kShellSteel.youngs_modulus * sec.thickness * H.norm() * 0.24 * 0.24);
        for (int k = 0; k < kPoints; ++k) EXPECT_LT((global_stress(fr, s, k) - expected).norm(), 1e-10 * expected.norm());
        EXPECT_NEAR(s.tau[0], 0.0, 1e-10 * expected.norm());
        EXPECT_NEAR(s.tau[1], 0.0, 1e-10 * expected.norm());
        Result r;
        forces(c, fr, s, r);
        for (int a = 0; a < 4; ++a) {
            f[q[a]] += r.force[a];
            m[q[a]] += r.moment[a];
        }
    }
    const double scale = expected.norm() * sec.thickness * 0.12;  // a typical nodal force
    for (int i : p.interior) {
        EXPECT_LT(f[i].norm(), 1e-12 * scale) << "interior node " << i;
        EXPECT_LT(m[i].norm(), 1e-12 * scale * 0.12) << "interior node " << i;
    }
}

// Bending patch test on a rectangular mesh: a constant curvature kappa (w = -kappa x^2 / 2,
// theta_y = kappa x) gives sigma_xx = -+ E/(1-nu^2) kappa t/2 at the bottom/top, sigma_yy = nu x that,
// no transverse shear, and zero net force and moment at the interior nodes.
TEST(ShellBtKernel, ConstantCurvaturePatchOnRectanglesIsExact) {
    const double t = 3e-3, kappa = 0.2;
    const Constants c = Constants::from(kShellSteel, {.thickness = t});
    const int nx = 3, ny = 2;
    const double lx = 0.09, ly = 0.05;
    std::vector<Vec3> X;
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) X.emplace_back(lx * i / nx, ly * j / ny, 0.0);
    std::vector<Vec3> f(X.size(), Vec3::Zero()), m(X.size(), Vec3::Zero());
    const double s_top = c.c11 * kappa * t / 2;  // bending stress magnitude at the surfaces
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const int a = j * (nx + 1) + i;
            const std::array<int, 4> q{a, a + 1, a + nx + 2, a + nx + 1};
            const auto Xe = element_nodes(X, q);
            const Frame fr = make_frame(Xe);
            std::array<Vec3, 4> du, dth;
            for (int k = 0; k < 4; ++k) {
                du[k] = Vec3(0, 0, -0.5 * kappa * Xe[k].x() * Xe[k].x());
                dth[k] = Vec3(0, kappa * Xe[k].x(), 0);  // theta_y = -dw/dx
            }
            State s;
            update_state(c, fr, du, dth, s);
            // u_x = z theta_y = z kappa x: eps_xx = kappa z, positive on top.
            EXPECT_NEAR(s.sigma[2][0], s_top, 1e-10 * s_top);
            EXPECT_NEAR(s.sigma[0][0], -s_top, 1e-10 * s_top);
            EXPECT_NEAR(s.sigma[2][1], kShellSteel.poissons_ratio * s_top, 1e-10 * s_top);
            EXPECT_NEAR(s.sigma[1][0], 0.0, 1e-10 * s_top);
            EXPECT_NEAR(s.tau[0], 0.0, 1e-10 * s_top);
            EXPECT_NEAR(s.tau[1], 0.0, 1e-10 * s_top);
            Result r;
            forces(c, fr, s, r);
            EXPECT_NEAR(std::sqrt(r.von_mises_sq[2]), s_top * std::sqrt(1 - 0.28 + 0.28 * 0.28), 1e-9 * s_top);
            for (int k = 0; k < 4; ++k) {
                f[q[k]] += r.force[k];
                m[q[k]] += r.moment[k];
            }
        }
    // Interior nodes: (1,1) and (2,1).
    const double moment_scale = s_top * t * t / 6 * ly / ny;
    for (int i : {nx + 2, nx + 3}) {
        EXPECT_LT(f[i].norm(), 1e-10 * moment_scale / (lx / nx)) << "node " << i;
        EXPECT_LT(m[i].norm(), 1e-10 * moment_scale) << "node " << i;
    }
}

// Objectivity: an element is stretched, bent and sheared (stresses in every component and in the
// hourglass resultants), then turned rigidly by 120 degrees about an oblique axis in 2000 steps
// (nodes and nodal triads exactly rotated). The stored stresses must not change and the nodal
// forces must turn with the element; a step-sized rigid rotation of a stress-free element gives no
// stress at all.
TEST(ShellBtKernel, LargeRigidRotationKeepsStressAndTurnsForces) {
    const Constants c = Constants::from(kShellSteel, {.thickness = 2e-3});
    const std::array<Vec3, 4> X{Vec3(0, 0, 0), Vec3(0.02, 0.001, 0), Vec3(0.021, 0.017, 0.0005), Vec3(-0.002, 0.015, 0)};
    State s;
    Result r0;
    std::array<Vec3, 4> x1, dth;
    const Vec3 u[4] = {Vec3(0, 0, 0), Vec3(2e-6, 1e-6, 3e-6), Vec3(1e-6, -1e-6, -2e-6), Vec3(-1e-6, 2e-6, 1e-6)};
    const Vec3 th[4] = {Vec3(1e-4, -2e-4, 0), Vec3(0, 3e-4, 1e-4), Vec3(-1e-4, 0, 0), Vec3(2e-4, 1e-4, 0)};
    for (int a = 0; a < 4; ++a) {
        x1[a] = X[a] + u[a];
        dth[a] = th[a];
    }
    internal_force(c, X, x1, dth, s, r0);
    ASSERT_FALSE(r0.bad);
    const State s0 = s;
    const double smax = std::sqrt(std::max({r0.von_mises_sq[0], r0.von_mises_sq[1], r0.von_mises_sq[2]}));
    ASSERT_GT(smax, 1e5);
    double hg_max = 0;
    for (double q : s0.hourglass) hg_max = std::max(hg_max, std::abs(q));
    ASSERT_GT(hg_max, 0.0);

    const Vec3 axis(0.3, -0.5, 0.8), centre(0.01, 0.01, 0.0);
    const int steps = 2000;
    const double total = 2 * std::numbers::pi / 3;
    Result r;
    std::array<Vec3, 4> x_old = x1, x_new;
    Mat3 R_old = Mat3::Identity();
    for (int k = 1; k <= steps; ++k) {
        const Mat3 R = rotation(total * k / steps, axis);
        const Vec3 inc = rotation_increment(R, R_old);
        for (int a = 0; a < 4; ++a) {
            x_new[a] = centre + R * (x1[a] - centre);
            dth[a] = inc;
        }
        internal_force(c, x_old, x_new, dth, s, r);
        ASSERT_FALSE(r.bad);
        x_old = x_new;
        R_old = R;
    }
    for (int p = 0; p < kPoints; ++p)
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(s.sigma[p][i], s0.sigma[p][i], 1e-9 * smax) << p << "," << i;
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(s.tau[i], s0.tau[i], 1e-9 * smax);
    for (int i = 0; i < 5; ++i) EXPECT_NEAR(s.hourglass[i], s0.hourglass[i], 1e-9 * hg_max);
    const Mat3 R = rotation(total, axis);
    double fmax = 0;
    for (int a = 0; a < 4; ++a) fmax = std::max(fmax, r0.force[a].norm());
    for (int a = 0; a < 4; ++a) {
        EXPECT_LT((r.force[a] - R * r0.force[a]).norm(), 1e-8 * fmax) << "node " << a;
        EXPECT_LT((r.moment[a] - R * r0.moment[a]).norm(), 1e-8 * fmax * 0.02) << "node " << a;
    }
    // A stress-free element turned by a large step (0.3 rad at once): no stress at all.
    State free;
    std::array<Vec3, 4> xr;
    const Mat3 Rb = rotation(0.3, axis);
    const Vec3 inc = rotation_increment(Rb, Mat3::Identity());
    for (int a = 0; a < 4; ++a) {
        xr[a] = Rb * X[a];
        dth[a] = inc;
    }
    internal_force(c, X, xr, dth, free, r);
    for (int p = 0; p < kPoints; ++p)
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(free.sigma[p][i], 0.0, 1e-6 * smax);
}

// Zero-energy modes of the linear stiffness. Element, with hourglass control and the drilling
// penalty: the six rigid-body modes and the one-point shear's rotation mode theta = (x - x_c,
// y - y_c) (zero curvature, shear zero at the centre only), which is not communicable: neighbouring
// elements have different centres, so no mesh can assemble it (Belytschko, Tsay and Liu 1981). With
// neither (formulation 2 as published without hourglass control): 9 more, the four drilling
// rotations and the five hourglass modes (two membrane, one transverse, two bending). Symmetric.
// Assembled free flat plate: only the six rigid-body modes with the drilling penalty, and one
// drilling rotation per node more without it (no spurious mesh mode either way).
TEST(ShellBtKernel, StiffnessHasOnlyRigidAndNonCommunicableZeroModes) {
    const std::array<Vec3, 4> X{Vec3(0, 0, 0), Vec3(0.02, 0.002, 0), Vec3(0.019, 0.018, 0), Vec3(0.001, 0.016, 0)};
    // Rotations scaled by the element size so that the eigenvalues are comparable.
    auto zero_modes = [](const Eigen::MatrixXd& K, double size) {
        Eigen::VectorXd s = Eigen::VectorXd::Ones(K.rows());
        for (int i = 0; i < K.rows(); ++i)
            if (i % 6 >= 3) s[i] = 1.0 / size;
        const Eigen::MatrixXd Ks = s.asDiagonal() * (0.5 * (K + K.transpose())) * s.asDiagonal();
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Ks);
        const auto& ev = eig.eigenvalues();
        int zeros = 0;
        for (int i = 0; i < ev.size(); ++i) zeros += std::abs(ev[i]) < 1e-10 * ev[ev.size() - 1];
        return zeros;
    };
    for (double r : {0.01, 0.0}) {
        ShellSection sec{.thickness = 1e-3, .hourglass_membrane = r, .hourglass_bending = r, .hourglass_transverse = r,
                         .drilling = r > 0 ? 1e-3 : 0.0};
        const Constants c = Constants::from(kShellSteel, sec);
        const auto K = linear_stiffness(c, X);
        EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
        EXPECT_EQ(zero_modes(K, 0.02), r > 0 ? 7 : 16) << "hourglass coefficient " << r;
        // The six rigid-body modes give no force.
        for (int k = 0; k < 6; ++k) {
            Eigen::Matrix<double, 24, 1> v = Eigen::Matrix<double, 24, 1>::Zero();
            for (int I = 0; I < 4; ++I) {
                if (k < 3) {
                    v[6 * I + k] = 1.0;
                } else {
                    const Vec3 w = Vec3::Unit(k - 3), d = w.cross(X[I]);
                    v.segment<3>(6 * I) = d;
                    v.segment<3>(6 * I + 3) = w;
                }
            }
            EXPECT_LT((K * v).norm(), 1e-9 * K.norm() * v.norm()) << "rigid mode " << k;
        }
        // The non-communicable mode: theta_x = x - x_c, theta_y = y - y_c in the element's frame.
        const Frame f = make_frame(X);
        const Vec3 centre = 0.25 * (X[0] + X[1] + X[2] + X[3]);
        Eigen::Matrix<double, 24, 1> v = Eigen::Matrix<double, 24, 1>::Zero();
        for (int I = 0; I < 4; ++I) {
            const Vec3 d = f.E.transpose() * (X[I] - centre);
            v.segment<3>(6 * I + 3) = f.E * Vec3(d.x(), d.y(), 0.0);
        }
        EXPECT_LT((K * v).norm(), 1e-9 * K.norm() * v.norm() * 0.02);
    }
    // A free flat 3 x 3 plate of distorted elements, 16 nodes: 6 zero modes, 6 + 16 = 22 without
    // the drilling penalty.
    std::vector<Vec3> nodes;
    for (int j = 0; j <= 3; ++j)
        for (int i = 0; i <= 3; ++i)
            nodes.emplace_back(0.01 * i + 0.002 * ((i * j) % 2), 0.01 * j + 0.0015 * (((i + 2) * j) % 3 == 1), 0.0);
    for (double drilling : {1e-3, 0.0}) {
        Eigen::MatrixXd K = Eigen::MatrixXd::Zero(6 * 16, 6 * 16);
        const Constants c = Constants::from(kShellSteel, {.thickness = 1e-3, .drilling = drilling});
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
                const int a = 4 * j + i;
                const std::array<int, 4> q{a, a + 1, a + 5, a + 4};
                const auto Ke = linear_stiffness(c, {nodes[q[0]], nodes[q[1]], nodes[q[2]], nodes[q[3]]});
                for (int I = 0; I < 4; ++I)
                    for (int J = 0; J < 4; ++J) K.block<6, 6>(6 * q[I], 6 * q[J]) += Ke.block<6, 6>(6 * I, 6 * J);
            }
        EXPECT_EQ(zero_modes(K, 0.01), drilling > 0 ? 6 : 22) << "drilling " << drilling;
    }
}

// Triangles as degenerate quadrilaterals: the constant-strain triangle's membrane stress for a
// linear field, no hourglass resultant whatever the nodal motion, mass rho t A / 3 per node, the
// Table 2-1 triangle step, and only the rigid-body modes at zero energy.
TEST(ShellBtKernel, DegenerateTriangleIsTheConstantStrainTriangle) {
    const Constants c = Constants::from(kShellSteel, {.thickness = 1e-3});
    const std::array<Vec3, 4> X{Vec3(0, 0, 0), Vec3(0.01, 0, 0), Vec3(0.003, 0.008, 0), Vec3(0.003, 0.008, 0)};
    const Frame f = make_frame(X);
    EXPECT_NEAR(f.area, 0.5 * 0.01 * 0.008, 1e-16);
    std::array<Vec3, 4> du, dth;
    const Vec3 arbitrary[3] = {Vec3(1e-6, -2e-6, 3e-6), Vec3(-1e-6, 1e-6, 2e-6), Vec3(2e-6, 0, -1e-6)};
    for (int a = 0; a < 4; ++a) {
        du[a] = arbitrary[std::min(a, 2)];
        dth[a] = Vec3(1e-4 * a, -2e-4, 5e-5 * a * a);
    }
    dth[3] = dth[2];
    State s;
    update_state(c, f, du, dth, s);
    for (int i = 0; i < 5; ++i) EXPECT_NEAR(s.hourglass[i], 0.0, 1e-20);
    // Constant strain of u = (2e-4 x, -1e-4 y): sigma_xx = c11 (2e-4 - nu 1e-4).
    for (int a = 0; a < 4; ++a) {
        du[a] = Vec3(2e-4 * X[a].x(), -1e-4 * X[a].y(), 0);
        dth[a] = Vec3::Zero();
    }
    State s2;
    update_state(c, f, du, dth, s2);
    EXPECT_NEAR(s2.sigma[1][0], c.c11 * 2e-4 - c.c12 * 1e-4, 1e-9 * c.c11 * 2e-4);
    EXPECT_NEAR(s2.sigma[1][1], c.c12 * 2e-4 - c.c11 * 1e-4, 1e-9 * c.c11 * 2e-4);
    const LumpedMass lm = lumped_mass(c, X, true);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(lm.mass[a], kShellSteel.density * 1e-3 * f.area / 3, 1e-18);
    EXPECT_EQ(lm.mass[3], 0.0);
    const std::array<Vec3, 3> tri{X[0], X[1], X[2]};
    EXPECT_DOUBLE_EQ(critical_time_step(kShellSteel, X, true),
                     cfl::triangle_shell_length(tri) / plate_wave_speed(kShellSteel));
    // Zero-energy modes of the triangle (repeated node folded in): the six rigid-body modes and, as
    // for the quadrilateral, the non-communicable rotation mode theta = (x - x_c, y - y_c) (the
    // rotational part c of the MITC3 shear field, zero at the centroid); none in a mesh (below).
    const auto K = linear_stiffness(c, X);
    Eigen::Matrix<double, 18, 18> Kt = Eigen::Matrix<double, 18, 18>::Zero();
    for (int I = 0; I < 4; ++I)
        for (int J = 0; J < 4; ++J) Kt.block<6, 6>(6 * std::min(I, 2), 6 * std::min(J, 2)) += K.block<6, 6>(6 * I, 6 * J);
    EXPECT_LT((Kt - Kt.transpose()).norm(), 1e-12 * Kt.norm());
    Eigen::Matrix<double, 18, 1> sc = Eigen::Matrix<double, 18, 1>::Ones();
    for (int i = 0; i < 18; ++i)
        if (i % 6 >= 3) sc[i] = 1.0 / 0.01;
    const Eigen::MatrixXd scaled = sc.asDiagonal() * Kt * sc.asDiagonal();  // a MatrixXd: core/eigen_instances.hpp
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(scaled);
    int zeros = 0;
    for (int i = 0; i < 18; ++i) zeros += std::abs(eig.eigenvalues()[i]) < 1e-10 * eig.eigenvalues()[17];
    EXPECT_EQ(zeros, 7);
    for (int k = 3; k < 6; ++k) {  // rigid rotations
        Eigen::Matrix<double, 18, 1> v;
        for (int I = 0; I < 3; ++I) {
            const Vec3 w = Vec3::Unit(k - 3);
            v.segment<3>(6 * I) = w.cross(X[I]);
            v.segment<3>(6 * I + 3) = w;
        }
        EXPECT_LT((Kt * v).norm(), 1e-9 * Kt.norm() * v.norm()) << "rigid rotation " << k - 3;
    }
    // A free mesh of 8 triangles (a 2 x 2 square split along alternating diagonals, 9 nodes): the
    // six rigid-body modes only.
    std::vector<Vec3> nodes;
    for (int j = 0; j <= 2; ++j)
        for (int i = 0; i <= 2; ++i) nodes.emplace_back(0.01 * i, 0.01 * j, 0.0);
    Eigen::MatrixXd Km = Eigen::MatrixXd::Zero(54, 54);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            const int a = 3 * j + i;
            const int q[4] = {a, a + 1, a + 4, a + 3};
            const std::array<std::array<int, 3>, 2> tris =
                (i + j) % 2 ? std::array<std::array<int, 3>, 2>{{{q[0], q[1], q[2]}, {q[0], q[2], q[3]}}}
                            : std::array<std::array<int, 3>, 2>{{{q[0], q[1], q[3]}, {q[1], q[2], q[3]}}};
            for (const auto& tr : tris) {
                const int cn[4] = {tr[0], tr[1], tr[2], tr[2]};
                const auto Ke = linear_stiffness(c, {nodes[cn[0]], nodes[cn[1]], nodes[cn[2]], nodes[cn[3]]});
                for (int I = 0; I < 4; ++I)
                    for (int J = 0; J < 4; ++J) Km.block<6, 6>(6 * cn[I], 6 * cn[J]) += Ke.block<6, 6>(6 * I, 6 * J);
            }
        }
    Eigen::VectorXd scm = Eigen::VectorXd::Ones(54);
    for (int i = 0; i < 54; ++i)
        if (i % 6 >= 3) scm[i] = 1.0 / 0.01;
    const Eigen::MatrixXd Ks = scm.asDiagonal() * (0.5 * (Km + Km.transpose())) * scm.asDiagonal();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig_m(Ks);
    int zeros_m = 0;
    for (int i = 0; i < 54; ++i) zeros_m += std::abs(eig_m.eigenvalues()[i]) < 1e-10 * eig_m.eigenvalues()[53];
    EXPECT_EQ(zeros_m, 6);
}

// Rotational inertia scaling: on a thin square element the scaled inertia is m a^2 / 8.04 (the
// header's figure, from the row bound), far above the physical m t^2 / 12, and with it the
// element's own highest frequency (lumped masses, dense eigensolver) is set by the translations:
// checked on a square, a 3:1 rectangle, a skewed quad, a thick element and a triangle. The free
// element's omega_max exceeds the Table 2-1 value 2/dt by at most sqrt(1 + nu) (the free single
// element's dilatation mode; inside a mesh the Table step is the exact limit of the membrane
// modes, see test_shell_bt.cpp).
TEST(ShellBtKernel, RotationalInertiaKeepsRotationsOutOfTheTimeStep) {
    struct Case {
        const char* name;
        std::array<Vec3, 4> X;
        double t;
        bool tri;
    };
    const Case cases[] = {
        {"thin square", {Vec3(0, 0, 0), Vec3(0.01, 0, 0), Vec3(0.01, 0.01, 0), Vec3(0, 0.01, 0)}, 1e-4, false},
        {"square t = a/10", {Vec3(0, 0, 0), Vec3(0.01, 0, 0), Vec3(0.01, 0.01, 0), Vec3(0, 0.01, 0)}, 1e-3, false},
        {"3:1 rectangle", {Vec3(0, 0, 0), Vec3(0.03, 0, 0), Vec3(0.03, 0.01, 0), Vec3(0, 0.01, 0)}, 1e-3, false},
        {"skewed quad", {Vec3(0, 0, 0), Vec3(0.012, 0.002, 0), Vec3(0.015, 0.011, 0), Vec3(0.002, 0.009, 0)}, 1e-3, false},
        {"triangle", {Vec3(0, 0, 0), Vec3(0.01, 0, 0), Vec3(0.004, 0.009, 0), Vec3(0.004, 0.009, 0)}, 1e-3, true},
    };
    for (const auto& cs : cases) {
        const Constants c = Constants::from(kShellSteel, {.thickness = cs.t});
        const LumpedMass lm = lumped_mass(c, cs.X, cs.tri);
        const double dt = critical_time_step(kShellSteel, cs.X, cs.tri);
        if (std::string(cs.name) == "thin square") {
            // Thin limit of the row bound (bending terms ~ (t/a)^2 = 1e-4): J = m a^2 / y^2 with
            // kappa G/E (y^2 + 2 y) = 4 / (1 - nu^2).
            const double a = 0.01, m = lm.mass[0], nu = kShellSteel.poissons_ratio;
            const double kge = (5.0 / 6.0) / (2 * (1 + nu));
            const double y = -1 + std::sqrt(1 + 4 / ((1 - nu * nu) * kge));
            EXPECT_NEAR(lm.inertia[0] / (m * a * a), 1 / (y * y), 2e-3 / (y * y));
            std::printf("thin square: J = m a^2 / %.3f (closed form %.3f), physical m t^2/12 x %.0f\n",
                        m * a * a / lm.inertia[0], y * y, lm.inertia[0] / (m * cs.t * cs.t / 12));
        }
        // Element eigenvalues with its lumped masses (the distinct nodes of a triangle).
        auto K = linear_stiffness(c, cs.X);
        const int n = cs.tri ? 3 : 4;
        Eigen::MatrixXd Kd = Eigen::MatrixXd::Zero(6 * n, 6 * n);
        for (int I = 0; I < 4; ++I)
            for (int J = 0; J < 4; ++J)
                Kd.block<6, 6>(6 * std::min(I, n - 1), 6 * std::min(J, n - 1)) += K.block<6, 6>(6 * I, 6 * J);
        Eigen::VectorXd minv(6 * n);
        for (int a = 0; a < n; ++a)
            for (int d = 0; d < 6; ++d) minv[6 * a + d] = 1.0 / std::sqrt(d < 3 ? lm.mass[a] : lm.inertia[a]);
        const Eigen::MatrixXd A = minv.asDiagonal() * Kd * minv.asDiagonal();
        const Eigen::MatrixXd symmetric = 0.5 * (A + A.transpose());  // a named matrix: core/eigen_instances.hpp
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(symmetric);
        const double wmax = std::sqrt(eig.eigenvalues().maxCoeff());
        // The same with the rotational rows only (translations held): what the scaling controls.
        Eigen::MatrixXd Ar(3 * n, 3 * n);
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b) Ar.block<3, 3>(3 * a, 3 * b) = A.block<3, 3>(6 * a + 3, 6 * b + 3);
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig_r(Ar);
        const double wrot = std::sqrt(std::max(0.0, eig_r.eigenvalues().maxCoeff()));
        std::printf("%-16s J/(m A) = %.4f, omega_max dt/2 = %.4f (rotations held fixed: translations; rotations alone "
                    "%.4f)\n",
                    cs.name, lm.inertia[0] / (lm.mass[0] * make_frame(cs.X).area), wmax * dt / 2, wrot * dt / 2);
        EXPECT_LE(wrot * dt / 2, 1.0) << cs.name;
        EXPECT_LE(wmax * dt / 2, std::sqrt(1 + kShellSteel.poissons_ratio) * 1.02) << cs.name;
    }
}

TEST(ShellBtKernel, BadSectionIsRefusedWithTheOwnerNamed) {
    try {
        ShellSection{.thickness = -1e-3}.validate("part 'perch'");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("part 'perch'"), std::string::npos) << e.what();
    }
    EXPECT_THROW((ShellSection{.thickness = 1e-3, .hourglass_bending = -0.1}.validate("x")), InputError);
    EXPECT_THROW((ShellSection{.thickness = 1e-3, .shear_factor = 0.0}.validate("x")), InputError);
}
