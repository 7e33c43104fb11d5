// The planar rigid wall (contact/rigid_wall.hpp, LS-DYNA *RIGIDWALL_PLANAR, penalty) against closed
// forms. Tolerances with their reasons, written before the runs:
//  - A block dropped on the wall (no gravity, v0 = 1 m/s) leaves it with its speed: mean z velocity
//    +v0 within 2 % (the penalty springs are 1/100 of the block's own Eq 2-30 stiffness, so the
//    block bounces nearly as a rigid mass on springs; what it keeps as vibration and what bulk
//    viscosity takes is a few 1e-3 of the energy), and its contact time is the rigid mass-on-springs
//    pi sqrt(m / sum k) within 5 % (the block's compliance in series adds a few %).
//  - Energy balance with the wall's work booked: at the deepest point of the bounce the solver's
//    "contact" energy (minus the work of the wall's forces) equals the wall's stored 1/2 sum k g^2
//    within 1 % of the impact energy (the central-difference work lags the state function by
//    O(dt / t_c)), and the run's balance error stays below 1e-3 of it.
//  - Frictionless: a block pressed onto the wall and sliding along it keeps its tangential momentum
//    to round-off (1e-12 relative): the wall's force has no tangential part.
//  - The same springs as a rigid part's faces in the plane (ContactInterface with a rigid master):
//    the two give the same run to round-off (positions within 1e-12 m after the bounce): the wall is
//    the segment contact's plane without the search.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../explicit/explicit_test_support.hpp"
#include "contact/contact.hpp"
#include "contact/explicit_contact.hpp"
#include "contact/rigid_wall.hpp"
#include "mesh/mesh.hpp"

using namespace fem;
using fem::test::input_error;
using fem::test::quiet;
using namespace fem::contact;

namespace {

const ElasticMaterial kBlock = ElasticMaterial::make("block", 1e7, 0.3, 1000);
constexpr double kSide = 0.02, kGap = 1e-3, kV0 = 1.0, kScale = 0.01;

// A 20 mm cube of 2 x 2 x 2 hexahedra kGap above the plane z = 0, moving at `v` (towards -z).
Mesh block_mesh() {
    Mesh mesh = box_hex8(kSide, kSide, kSide, 2, 2, 2, "block");
    mesh.translate(Vec3(-0.5 * kSide, -0.5 * kSide, kGap));
    return mesh;
}

struct Bounce {
    double vz_after = 0, contact_time = 0, mass = 0, springs = 0;  // springs: sum of the bottom nodes' k
    double contact_energy_deepest = 0, stored_deepest = 0, energy_error = 0, impact_energy = 0;
    std::vector<Vec3> x_end;
};

// The block dropped on the wall (wall = true) or on a fixed rigid quad plate in the same plane, run
// to end_time; the contact time counts cycles with a non-zero reaction.
Bounce drop(bool wall, double end_time, Vec3 v0 = Vec3(0, 0, -kV0)) {
    Mesh mesh = block_mesh();
    const int n_block = mesh.node_count();
    if (!wall) mesh.append(parallelogram_quad4(Vec3::Zero(), Vec3(0.1, 0, 0), Vec3(0, 0.1, 0), 4, 4, "ground"));
    ExplicitModel model(mesh);
    model.add_hex8("block", kBlock);
    std::vector<int> block_nodes(n_block);
    for (int i = 0; i < n_block; ++i) block_nodes[i] = i;
    model.set_initial_velocity(block_nodes, v0);
    auto slave = ContactSurface::from_part(mesh, "block", kBlock);
    Bounce b;
    for (std::size_t i = 0; i < slave.nodes.size(); ++i)
        if (std::abs(mesh.nodes[slave.nodes[i]].z() - kGap) < 1e-12) b.springs += kScale * slave.node_stiffness[i];
    PlanarWall* w = nullptr;
    ContactInterface* c = nullptr;
    if (wall) {
        w = &add_rigid_wall(model, PlanarWall("block on wall", Vec3::Zero(), Vec3::UnitZ(), slave, {kScale, 0.01}));
    } else {
        model.add_rigid_part("ground", RigidMotion::fixed());
        ContactOptions co;
        co.penalty_scale = kScale;
        c = &add_contact(model, ContactInterface("block on ground", slave, ContactSurface::rigid_part(mesh, "ground", 0.01), co));
    }
    ExplicitSolver solver(model, quiet(end_time));
    double t_prev = 0, deepest = 0;
    solver.observer = [&](const ExplicitSolver& s) {
        const double dt = s.time() - t_prev;
        t_prev = s.time();
        const double f = w ? w->force_on_wall().norm() : c->force_on_master().norm();
        if (f > 0) b.contact_time += dt;
        if (w && w->stored_energy() > deepest) deepest = w->stored_energy();
    };
    const RunSummary sum = solver.run();
    double m = 0, p = 0;
    for (int i = 0; i < n_block; ++i) {
        m += solver.state().mass[i];
        p += solver.state().mass[i] * solver.state().v[i].z();
    }
    b.mass = m;
    b.vz_after = p / m;
    b.contact_energy_deepest = sum.energy.contact;
    b.stored_deepest = deepest;
    b.energy_error = sum.energy.max_abs_balance_error;
    b.impact_energy = 0.5 * m * v0.squaredNorm();
    b.x_end.assign(solver.state().x.begin(), solver.state().x.begin() + n_block);
    return b;
}

}  // namespace

TEST(RigidWall, BlockDroppedOnTheWallReboundsWithItsSpeed) {
    // Contact begins at kGap / v0 = 1 ms; mass-on-springs contact time pi sqrt(m / K).
    const Bounce probe = drop(true, 1e-4);
    const double tc = std::numbers::pi * std::sqrt(probe.mass / probe.springs);
    const double end = kGap / kV0 + 1.5 * tc;
    const Bounce b = drop(true, end);
    std::printf("[ wall ] m %.4g kg, K %.4g N/m: contact %.4g ms (pi sqrt(m/K) %.4g ms), rebound %.5f m/s, "
                "balance error %.3g of the impact energy\n",
                b.mass, b.springs, 1e3 * b.contact_time, 1e3 * tc, b.vz_after, b.energy_error / b.impact_energy);
    EXPECT_NEAR(b.vz_after / kV0, 1.0, 0.02);
    EXPECT_NEAR(b.contact_time / tc, 1.0, 0.05);
    EXPECT_LT(b.energy_error / b.impact_energy, 1e-3);
}

TEST(RigidWall, EnergyBalanceBooksTheWallsWork) {
    const Bounce probe = drop(true, 1e-4);
    const double tc = std::numbers::pi * std::sqrt(probe.mass / probe.springs);
    const Bounce b = drop(true, kGap / kV0 + 0.5 * tc);  // stops at the deepest point
    std::printf("[ wall ] at the deepest point: contact energy %.5g J, stored %.5g J (impact %.5g J), balance error %.3g\n",
                b.contact_energy_deepest, b.stored_deepest, b.impact_energy, b.energy_error / b.impact_energy);
    EXPECT_GT(b.stored_deepest, 0.5 * b.impact_energy);  // most of the energy is in the springs there
    EXPECT_NEAR(b.contact_energy_deepest, b.stored_deepest, 0.01 * b.impact_energy);
    EXPECT_LT(b.energy_error / b.impact_energy, 1e-3);
}

TEST(RigidWall, ANodeSlidingAlongTheWallFeelsNoFriction) {
    // The block slides at 2 m/s along x while it bounces: its x momentum stays 2 m/s x m.
    const Bounce probe = drop(true, 1e-4);
    const double tc = std::numbers::pi * std::sqrt(probe.mass / probe.springs);
    Mesh mesh = block_mesh();
    ExplicitModel model(mesh);
    model.add_hex8("block", kBlock);
    std::vector<int> nodes(mesh.node_count());
    for (int i = 0; i < mesh.node_count(); ++i) nodes[i] = i;
    model.set_initial_velocity(nodes, Vec3(2.0, 0, -kV0));
    auto& w = add_rigid_wall(model, PlanarWall("block on wall", Vec3::Zero(), Vec3::UnitZ(),
                                               ContactSurface::from_part(mesh, "block", kBlock), {kScale, 0.01}));
    ExplicitSolver solver(model, quiet(kGap / kV0 + 1.2 * tc));
    double worst = 0, max_normal = 0;
    solver.observer = [&](const ExplicitSolver& s) {
        double p = 0, m = 0;
        for (int i : nodes) p += s.state().mass[i] * s.state().v[i].x(), m += s.state().mass[i];
        worst = std::max(worst, std::abs(p / m - 2.0) / 2.0);
        max_normal = std::max(max_normal, w.force_on_wall().norm());
    };
    solver.run();
    std::printf("[ wall ] sliding: largest normal force %.4g N, largest relative change of the x momentum %.3g\n",
                max_normal, worst);
    EXPECT_GT(max_normal, 0.0);
    EXPECT_LT(worst, 1e-12);
    EXPECT_EQ(w.force_on_wall().x(), 0.0);
}

TEST(RigidWall, SameRunAsARigidPartInThePlane) {
    const Bounce probe = drop(true, 1e-4);
    const double tc = std::numbers::pi * std::sqrt(probe.mass / probe.springs);
    const Vec3 v0(0.3, -0.2, -kV0);
    const Bounce a = drop(true, kGap / kV0 + 1.5 * tc, v0), b = drop(false, kGap / kV0 + 1.5 * tc, v0);
    double diff = 0;
    for (std::size_t i = 0; i < a.x_end.size(); ++i) diff = std::max(diff, (a.x_end[i] - b.x_end[i]).norm());
    std::printf("[ wall ] wall vs rigid plate: largest position difference %.3g m, rebound %.6f vs %.6f m/s\n", diff,
                a.vz_after, b.vz_after);
    EXPECT_LT(diff, 1e-12);
    EXPECT_GT(a.vz_after, 0.9 * kV0);
}

TEST(RigidWall, BadInputIsRefusedNamingTheWall) {
    const Mesh mesh = block_mesh();
    const auto s = ContactSurface::from_part(mesh, "block", kBlock);
    EXPECT_NE(input_error([&] { PlanarWall("w1", Vec3::Zero(), Vec3::Zero(), s); }).find("rigid wall 'w1': the normal"),
              std::string::npos);
    EXPECT_NE(input_error([&] { PlanarWall("w2", Vec3::Zero(), Vec3::UnitZ(), s, {0.0, 1.0}); }).find("rigid wall 'w2'"),
              std::string::npos);
    EXPECT_NE(input_error([&] { PlanarWall("w3", Vec3::Zero(), Vec3::UnitZ(), s, {0.1, -1.0}); }).find("depth"),
              std::string::npos);
}
