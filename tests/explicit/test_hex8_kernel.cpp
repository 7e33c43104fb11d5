// Element-level verification of the one-point hexahedron (element/hex8_explicit.hpp): patch test
// on a distorted mesh, rigid rotations, objectivity, small-strain limit, hourglass orthogonality.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/error.hpp"
#include "element/hex8_explicit.hpp"
#include "explicit/groups.hpp"
#include "mesh/mesh.hpp"
#include "explicit_test_support.hpp"

using namespace fem;
using namespace fem::test;

namespace {

std::array<Vec3, 8> unit_cube() {
    return {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
            Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
}

// Neo-Hookean Cauchy stress for a given F (the closed form the kernel must reproduce).
Mat3 neo_hookean_cauchy(const Mat3& F, const ElasticMaterial& m) {
    const double J = F.determinant(), mu = m.shear_modulus(), la = m.lame_lambda();
    return (mu * (F * F.transpose() - Mat3::Identity()) + la * std::log(J) * Mat3::Identity()) / J;
}

}  // namespace

TEST(Hex8Kernel, UniformGradientOfCubeAndVolume) {
    const auto ref = hex8::make_reference(unit_cube());
    EXPECT_NEAR(ref.volume, 1.0, 1e-14);
    // For a unit cube, B_a = integral of dN/dX = +-1/4 in each component.
    for (int a = 0; a < 8; ++a)
        for (int d = 0; d < 3; ++d) EXPECT_NEAR(std::abs(ref.B[a][d]), 0.25, 1e-14);
}

TEST(Hex8Kernel, InvertedElementIsRefusedWithItsName) {
    auto X = unit_cube();
    std::swap(X[4], X[0]);  // folds the element
    try {
        hex8::make_reference(X, "element 7");
        FAIL() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("element 7"), std::string::npos);
    }
}

// Patch test: a distorted 3x3x3 block, every node moved by a homogeneous deformation x = F X. Each
// element must get exactly that F (its stress the closed form) and the interior nodes must carry no
// net force; the hourglass forces must vanish.
TEST(Hex8Kernel, PatchTestOnDistortedMeshIsExact) {
    Mesh mesh = box_hex8(1, 1, 1, 3, 3, 3, "patch");
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(-0.08, 0.08);
    for (auto& x : mesh.nodes)
        if (x.x() > 1e-9 && x.x() < 1 - 1e-9 && x.y() > 1e-9 && x.y() < 1 - 1e-9 && x.z() > 1e-9 && x.z() < 1 - 1e-9)
            x += Vec3(u(rng), u(rng), u(rng));
    Hex8Options opt;
    opt.hourglass_qm = 0.1;
    Hex8Group group(mesh, 0, kRubber, opt);
    Mat3 F;
    F << 1.05, 0.02, -0.01, 0.03, 0.97, 0.015, -0.02, 0.01, 1.02;
    NodalState s;
    s.X = mesh.nodes;
    for (const auto& X : mesh.nodes) s.x.push_back(F * X);
    s.v.assign(mesh.node_count(), Vec3::Zero());
    s.f.assign(mesh.node_count(), Vec3::Zero());
    const auto r = group.internal_forces(s, false);
    const Mat3 sigma = neo_hookean_cauchy(F, kRubber);
    const double vm_exact = hex8::von_mises(sigma);
    for (double vm : group.element_stress()) EXPECT_NEAR(vm, vm_exact, 1e-9 * vm_exact);
    EXPECT_NEAR(r.hourglass_energy, 0.0, 1e-20);
    // Stored energy: V0 W(F), summed over the patch of volume 1.
    const double J = F.determinant(), mu = kRubber.shear_modulus(), la = kRubber.lame_lambda();
    const double W = 0.5 * mu * (F.squaredNorm() - 3) - mu * std::log(J) + 0.5 * la * std::log(J) * std::log(J);
    EXPECT_NEAR(r.internal_energy, W, 1e-10 * W);
    // Interior nodes: equilibrium of a constant stress.
    const double scale = sigma.norm() * (1.0 / 9.0);  // stress x face area of one element
    for (int i = 0; i < mesh.node_count(); ++i) {
        const Vec3& X = mesh.nodes[i];
        const bool interior = X.x() > 1e-9 && X.x() < 1 - 1e-9 && X.y() > 1e-9 && X.y() < 1 - 1e-9 &&
                              X.z() > 1e-9 && X.z() < 1 - 1e-9;
        if (interior) {
            EXPECT_LT(s.f[i].norm(), 1e-10 * scale) << "node " << i;
        }
    }
}

// Large rigid rotations (90 and 180 degrees about skew axes) of a distorted element produce neither
// strain nor hourglass energy nor forces: the formulation is objective.
TEST(Hex8Kernel, RigidRotationCreatesNoStrain) {
    auto X = unit_cube();
    X[6] += Vec3(0.1, -0.05, 0.08);
    X[1] += Vec3(0.05, 0.02, -0.03);
    const auto ref = hex8::make_reference(X);
    const auto mat = hex8::Hex8Material::from(kSteel, 0.1, 0.0, {}, true);
    for (double deg : {30.0, 90.0, 180.0}) {
        const Mat3 R = rotation(deg * std::numbers::pi / 180, Vec3(1, 2, 3));
        std::array<Vec3, 8> u, v;
        for (int a = 0; a < 8; ++a) {
            u[a] = R * X[a] + Vec3(5, -2, 1) - X[a];
            v[a].setZero();
        }
        hex8::Hex8Result r;
        hex8::internal_force(ref, mat, u, v, 0.0, r);
        // Round-off only: a non-objective (small-strain) element would store ~E V = 1e11 J here.
        // Round-off of the strain is ~1e-15, so energy ~ E V 1e-15 at most, forces ~ E A 1e-15.
        EXPECT_LT(std::abs(r.strain_energy), 1e-15 * kSteel.youngs_modulus * ref.volume) << deg;
        EXPECT_LT(r.hourglass_energy, 1e-15 * kSteel.youngs_modulus * ref.volume) << deg;
        for (const auto& f : r.force) EXPECT_LT(f.norm(), 1e-14 * kSteel.youngs_modulus) << deg;
    }
}

// Objectivity with strain: F = R U gives the same energy and von Mises stress as U, forces rotated.
TEST(Hex8Kernel, StretchThenRotateIsObjective) {
    const auto X = unit_cube();
    const auto ref = hex8::make_reference(X);
    const auto mat = hex8::Hex8Material::from(kRubber, 0.0, 0.0, {}, false);
    Mat3 U;
    U << 1.3, 0.1, 0.0, 0.1, 0.8, 0.05, 0.0, 0.05, 1.1;
    const Mat3 R = rotation(2.0, Vec3(-1, 0.5, 2));
    std::array<Vec3, 8> xu, xr, v;
    for (int a = 0; a < 8; ++a) {
        xu[a] = U * X[a] - X[a];
        xr[a] = R * U * X[a] - X[a];
        v[a].setZero();
    }
    hex8::Hex8Result ru, rr;
    hex8::internal_force(ref, mat, xu, v, 0.0, ru);
    hex8::internal_force(ref, mat, xr, v, 0.0, rr);
    EXPECT_NEAR(rr.strain_energy, ru.strain_energy, 1e-10 * ru.strain_energy);
    EXPECT_NEAR(rr.von_mises, ru.von_mises, 1e-10 * ru.von_mises);
    for (int a = 0; a < 8; ++a) EXPECT_LT((rr.force[a] - R * ru.force[a]).norm(), 1e-9 * ru.force[a].norm() + 1e-6);
}

// Small strain: uniaxial stretch eps with free lateral contraction -> sigma_xx = E eps (to O(eps)),
// checked through the stress of a uniaxial stress state F = diag(1+e, 1-nu e, 1-nu e).
TEST(Hex8Kernel, SmallStrainLimitIsLinearElastic) {
    const auto X = unit_cube();
    const auto ref = hex8::make_reference(X);
    const auto mat = hex8::Hex8Material::from(kRubber, 0.0, 0.0, {}, false);
    const double e = 1e-6, nu = kRubber.poissons_ratio;
    const Mat3 F = Eigen::Vector3d(1 + e, 1 - nu * e, 1 - nu * e).asDiagonal();
    std::array<Vec3, 8> x, v;
    for (int a = 0; a < 8; ++a) {
        x[a] = F * X[a] - X[a];
        v[a].setZero();
    }
    hex8::Hex8Result r;
    hex8::internal_force(ref, mat, x, v, 0.0, r);
    EXPECT_NEAR(r.cauchy(0, 0), kRubber.youngs_modulus * e, 1e-4 * kRubber.youngs_modulus * e);
    EXPECT_NEAR(r.cauchy(1, 1), 0.0, 2e-4 * kRubber.youngs_modulus * e);
    EXPECT_NEAR(r.strain_energy, 0.5 * kRubber.youngs_modulus * e * e, 1e-3 * 0.5 * kRubber.youngs_modulus * e * e);
}

// An hourglass mode is resisted (stored energy k/2 q^2 > 0) while producing no constant strain.
TEST(Hex8Kernel, HourglassModeIsResisted) {
    const auto X = unit_cube();
    const auto ref = hex8::make_reference(X);
    const auto mat = hex8::Hex8Material::from(kRubber, 0.1, 0.0, {}, false);
    std::array<Vec3, 8> x, v;
    const double h = 1e-3;
    for (int a = 0; a < 8; ++a) {
        const double sx = X[a].x() * 2 - 1, sy = X[a].y() * 2 - 1;
        x[a] = Vec3(0, 0, h * sx * sy);  // xi*eta mode in z (displacement)
        v[a].setZero();
    }
    hex8::Hex8Result r;
    hex8::internal_force(ref, mat, x, v, 0.0, r);
    EXPECT_LT(r.strain_energy, 1e-12 * r.hourglass_energy);
    // k = QM 2 mu sum|B|^2/(8 V0) = 0.1 * 2 mu * 8 * (3/16) / 8; q = sum gamma u = 8 h (gamma = h).
    const double k = 0.1 * 2 * kRubber.shear_modulus() * 1.5 / 8;
    EXPECT_NEAR(r.hourglass_energy, 0.5 * k * (8 * h) * (8 * h), 1e-9 * r.hourglass_energy);
}

