// Symmetry planes (half models) and gravity scaled by a curve.
//
// A half model with a symmetry plane must reproduce the full model's symmetric response: the
// discrete full model is mirror-symmetric (mirror-symmetric mesh, loads and initial state), so its
// solution is, and the half model is the same equations restricted to one side (the plane nodes
// carry half the mass, the normal translation and the in-plane rotations are zero by symmetry).
// Both run with the same steps, so they differ by round-off only (summation order): 1e-9 of the
// response.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "explicit_test_support.hpp"

using namespace fem;
using namespace fem::test;
using fem::test::quiet;

namespace {

// The node of `m` at X (exactly one), for comparing two meshes of one body.
int node_at(const Mesh& m, const Vec3& X) {
    for (int i = 0; i < m.node_count(); ++i)
        if ((m.nodes[i] - X).norm() < 1e-12) return i;
    return -1;
}
}  // namespace

// A rubber block stretched by a symmetric initial velocity field v = (10 x, -2 y, 0) [1/s]: the
// full block x in [-0.1, 0.1] against the half x in [0, 0.1] with a symmetry plane at x = 0.
TEST(SymmetryPlane, HalfBlockReproducesTheFullBlock) {
    Mesh full = box_hex8(0.2, 0.1, 0.05, 8, 4, 2, "block");
    full.translate(Vec3(-0.1, 0, 0));
    const Mesh half = box_hex8(0.1, 0.1, 0.05, 4, 4, 2, "block");
    const auto v0 = [](const Vec3& X) { return Vec3(10 * X.x(), -2 * X.y(), 0); };
    auto o = quiet(4e-3);
    o.fixed_dt = 2e-5;
    ExplicitModel mf(full);
    mf.add_hex8("block", kFingerRubber);
    mf.set_initial_velocity(v0);
    ExplicitSolver sf(mf, o);
    sf.run();
    ExplicitModel mh(half);
    mh.add_hex8("block", kFingerRubber);
    mh.set_initial_velocity(v0);
    const std::vector<int> plane = mh.add_symmetry_plane(Vec3(-1, 0, 0), Vec3::Zero());
    EXPECT_EQ(plane.size(), 5u * 3u);
    for (int n : plane) EXPECT_EQ(mh.fixed()[n], Dofs::x | Dofs::ry | Dofs::rz);
    ExplicitSolver sh(mh, o);
    sh.run();
    double umax = 0, diff = 0;
    for (int i = 0; i < half.node_count(); ++i) {
        const int j = node_at(full, half.nodes[i]);
        ASSERT_GE(j, 0);
        const Vec3 uf = sf.state().x[j] - full.nodes[j], uh = sh.state().x[i] - half.nodes[i];
        umax = std::max(umax, uf.norm());
        diff = std::max(diff, (uf - uh).norm());
    }
    std::printf("[ symmetry ] block: largest displacement %.4g mm, half - full %.3g m\n", 1e3 * umax, diff);
    EXPECT_GT(umax, 1e-4);  // a real response (0.8 mm)
    EXPECT_LT(diff, 1e-9 * umax);
}

// A steel beam clamped at both ends with a midspan force pulse (bending in the x-y plane): the full
// beam x in [-0.2, 0.2] against the half x in [0, 0.2] with the plane x = 0 through the midspan node,
// which then has u_x, theta_y and theta_z fixed and carries half the force.
TEST(SymmetryPlane, HalfBeamKeepsTheInPlaneRotationsFixed) {
    const double L = 0.2, F = 0.5;
    const BeamOptions section{beam::Section::circular(2e-3)};
    auto o = quiet(3e-3);  // the automatic step: the same in both (the same element lengths, no measurement for beams)
    const Mesh full = line_beam2(Vec3(-L, 0, 0), Vec3(L, 0, 0), 20, "beam");
    ExplicitModel mf(full);
    mf.add_beams("beam", kWireSteel, section);
    mf.fix({0, 20});
    mf.add_nodal_force({10}, Vec3(0, F, 0), Curve::pulse(0.0, 1e-3));
    ExplicitSolver sf(mf, o);
    sf.run();
    const Mesh half = line_beam2(Vec3::Zero(), Vec3(L, 0, 0), 10, "beam");
    ExplicitModel mh(half);
    mh.add_beams("beam", kWireSteel, section);
    mh.fix(half.node_set("end"));
    const std::vector<int> plane = mh.add_symmetry_plane(Vec3::UnitX(), Vec3::Zero());
    ASSERT_EQ(plane, std::vector<int>{0});
    mh.add_nodal_force({0}, Vec3(0, 0.5 * F, 0), Curve::pulse(0.0, 1e-3));
    ExplicitSolver sh(mh, o);
    sh.run();
    double umax = 0, diff = 0, rot = 0;
    for (int i = 0; i <= 10; ++i) {
        const int j = 10 + i;
        const Vec3 uf = sf.state().x[j] - full.nodes[j], uh = sh.state().x[i] - half.nodes[i];
        umax = std::max(umax, uf.norm());
        diff = std::max(diff, (uf - uh).norm());
    }
    const Mat3& R0 = sh.state().rotation[sh.state().rot_index[0]];
    rot = (R0 - Mat3::Identity()).norm();  // theta_y = theta_z = 0; theta_x stays 0 (no torsion)
    std::printf("[ symmetry ] beam: midspan deflection %.4g mm, half - full %.3g m\n", 1e3 * umax, diff);
    EXPECT_GT(umax, 1e-5);
    EXPECT_LT(diff, 1e-9 * umax);
    EXPECT_EQ(rot, 0.0);
}

TEST(SymmetryPlane, SkewNormalsAndEmptyPlanesAreRefused) {
    const Mesh mesh = box_hex8(0.1, 0.1, 0.1, 2, 2, 2, "block");
    ExplicitModel model(mesh);
    try {
        model.add_symmetry_plane(Vec3(1, 1, 0), Vec3::Zero());
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("not along a global axis"), std::string::npos) << e.what();
    }
    EXPECT_THROW(model.add_symmetry_plane(Vec3::Zero(), Vec3::Zero()), InputError);
    EXPECT_THROW(model.add_symmetry_plane(Vec3::UnitZ(), Vec3(0, 0, 0.07)), InputError);  // no node at z = 0.07
    EXPECT_EQ(model.add_symmetry_plane(Vec3::UnitZ(), Vec3(0, 0, 0.05)).size(), 9u);
    model.add_symmetry_plane(Vec3(0, -2, 0), mesh.node_set("y0"));
    EXPECT_EQ(model.fixed()[mesh.node_set("y0")[0]] & Dofs::y, Dofs::y);
}

// Gravity scaled by a curve: a free wire under g x ramp(t) (0 -> 1 over 1 ms, held). Central
// differences integrate the force at the step times: the velocity is g times the integral of the
// curve, to O(dt) (the half-step offset of the force samples; the ramp's kink): within g dt.
TEST(Gravity, ScaledByACurve) {
    const Mesh mesh = line_beam2(Vec3::Zero(), Vec3(0.1, 0, 0), 2, "wire");
    ExplicitModel model(mesh);
    model.add_beams("wire", kWireSteel, {beam::Section::circular(1e-3)});
    const double g = 9.81;
    const Curve ramp({{0, 0}, {1e-3, 1}}, "ramp");
    model.set_gravity(Vec3(0, 0, -g), ramp);
    ExplicitSolver solver(model, quiet(3e-3));
    const RunSummary sum = solver.run();
    const double dt = sum.max_dt, t = solver.time();
    EXPECT_NEAR(solver.state().v[0].z(), -g * ramp.integral(t - 0.5 * dt), g * dt);
    EXPECT_LT(sum.energy.relative_error(), 1e-9);
}
