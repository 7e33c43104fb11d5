// Mass-proportional damping relative to a rigid motion (explicit/relative_damping.hpp): the body's
// motion with the frame is not damped, its motion relative to the frame is, at Eq 2-39's rate.
#include <gtest/gtest.h>

#include <cmath>

#include "explicit/relative_damping.hpp"
#include "explicit_test_support.hpp"

using namespace fem;
using namespace fem::test;

namespace {

struct Drift {
    Vec3 velocity;      // the block's mass-weighted mean velocity at the end
    RunSummary summary;
};

// A free 2 x 2 x 2 rubber block moving at v0, damped at alpha [1/s] either absolutely or relative to a
// frame translating at `frame_velocity`; no gravity, so every node keeps the same velocity and the
// block stays unstrained: the mean velocity is the closed form of a damped point mass.
constexpr double kStep = 4e-5;  // below the block's critical step (about 5e-5 s)

Drift drifting_block(const Vec3& v0, double alpha, const Vec3* frame_velocity, double t_end) {
    const Mesh mesh = box_hex8(0.02, 0.02, 0.02, 2, 2, 2, "block");
    ExplicitModel model(mesh);
    model.add_hex8("block", kFingerRubber);
    if (frame_velocity) set_relative_mass_damping(model, "block", alpha, RigidMotion::translation(*frame_velocity), "the belt");
    else model.set_mass_damping("block", alpha);
    model.set_initial_velocity(mesh.nodes_of_part("block"), v0);
    ExplicitOptions o = quiet(t_end);
    o.fixed_dt = kStep;
    ExplicitSolver solver(model, o);
    Drift d;
    d.summary = solver.run();
    double m = 0.0;
    d.velocity = Vec3::Zero();
    for (int i = 0; i < mesh.node_count(); ++i) d.velocity += solver.state().mass[i] * solver.state().v[i], m += solver.state().mass[i];
    d.velocity /= m;
    return d;
}

}  // namespace

// v(t) = V + (v0 - V) exp(-alpha t) relative to a frame moving at V; exp(-alpha t) v0 without it.
// The velocities are the mid-step ones, v(t_end - dt/2); the central-difference damping of Eq 2-39
// (at the mid-point) decays by (1 - alpha dt/2) / (1 + alpha dt/2) per step, exp(-alpha dt) to
// (alpha dt)^3 / 12: 1e-9 relative over the 500 steps at alpha dt = 2e-3, so 1e-6 is a strict bound
// (the velocity taken at t_end instead of t_end - dt/2 misses it by 6e-4 relative).
TEST(RelativeDamping, ABodyRelaxesToTheFramesVelocityNotToRest) {
    const Vec3 v0(1.0, -0.4, 0.2), V(0.5, 0.2, 0.0);
    const double alpha = 50.0, t_end = 0.02;  // alpha t = 1
    const Drift relative = drifting_block(v0, alpha, &V, t_end);
    const Drift absolute = drifting_block(v0, alpha, nullptr, t_end);
    const double t = relative.summary.end_time - 0.5 * kStep, decay = std::exp(-alpha * t);
    EXPECT_LT((relative.velocity - (V + (v0 - V) * decay)).norm(), 1e-6 * v0.norm()) << relative.velocity.transpose();
    EXPECT_LT((absolute.velocity - v0 * decay).norm(), 1e-6 * v0.norm()) << absolute.velocity.transpose();
    // The frame's term does work on the block: booked with the force providers, the balance holds.
    EXPECT_LT(relative.summary.energy.relative_error(), 1e-6);
    EXPECT_GT(std::abs(relative.summary.energy.contact), 1e-3 * relative.summary.energy.damping);
}

// A block spinning with a frame that turns at the same rate about the same axis is not damped at
// all: it follows the rigid rotation as the undamped block of ExplicitRotation.RigidSpinCreatesNoStrainEnergy
// does, where damping the absolute velocity at the same alpha would have slowed it to exp(-alpha t).
TEST(RelativeDamping, ABodyTurningWithTheFrameIsNotDamped) {
    const double a = 0.1, alpha = 30.0;
    Mesh mesh = box_hex8(a, a, a, 3, 3, 3, "block");
    mesh.translate(Vec3(-a / 2, -a / 2, -a / 2));
    const Vec3 w = 100.0 * Vec3(1, 1, 2).normalized();
    const double t_end = kPi / w.norm();  // alpha t = 0.94: absolute damping would lose 61 % of the speed
    auto spinning = [&](bool relative) {
        ExplicitModel model(mesh);
        model.add_hex8("block", kSteel);
        if (relative) set_relative_mass_damping(model, "block", alpha, RigidMotion::rotation(Vec3::Zero(), w, Curve::constant(w.norm())), "the turntable");
        else model.set_mass_damping("block", alpha);
        model.set_initial_velocity([&](const Vec3& X) { return Vec3(w.cross(X)); });
        return run_rigid_spin(model, mesh, w, t_end);
    };
    const RigidSpin relative = spinning(true), absolute = spinning(false);
    EXPECT_LT(relative.position_error, 1e-4 * a);
    EXPECT_LT(relative.max_internal_over_kinetic, 1e-5);
    EXPECT_GT(absolute.position_error, 0.05 * a);  // the damped block lags the rotation by centimetres
}

TEST(RelativeDamping, BadInputIsRefusedNamingTheCulprit) {
    const RigidMotion still;
    EXPECT_NE(input_error([&] { RelativeMassDamping("skin", still, {{3, -1.0}}); }).find("skin: alpha = -1 of node 3"), std::string::npos);
    EXPECT_NE(input_error([&] { RelativeMassDamping("skin", still, {{3, 1.0}, {3, 2.0}}); }).find("node 3 is listed twice"), std::string::npos);
    const Mesh mesh = box_hex8(0.02, 0.02, 0.02, 1, 1, 1, "block");
    ExplicitModel model(mesh);
    model.add_hex8("block", kFingerRubber);
    model.add_force_provider(std::make_unique<RelativeMassDamping>("skin", still, std::vector<std::pair<int, double>>{{8, 1.0}}));
    EXPECT_NE(input_error([&] { ExplicitSolver(model, quiet(1e-4)).run(); }).find("skin: node 8 is not in the model (8 nodes)"), std::string::npos);
    EXPECT_NE(input_error([&] { set_relative_mass_damping(model, "no such part", 1.0, still, "x"); }).find("no such part"), std::string::npos);
}
