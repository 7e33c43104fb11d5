// Nodes tied to a shell node at an offset (explicit/offset_tie.hpp): carried rigidly by the
// anchor's rotation, and bad input refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/error.hpp"
#include "explicit/offset_tie.hpp"
#include "explicit_test_support.hpp"

using namespace fem;

// A flat steel patch with two point masses 20 mm above and below its centre node, tied to it,
// spinning freely about an in-plane axis through the centre (a principal axis of the whole): the
// masses must go round with the patch (position within 1e-4 of the size, as the shell's own spin
// test), the springs store next to nothing, and the balance holds.
TEST(OffsetTie, TiedMassesTurnWithTheirShellAnchor) {
    Mesh mesh = rectangle_quads(0.06, 0.06, 6, 6, ElementShape::Quad4, "patch");
    for (auto& p : mesh.nodes) p -= Vec3(0.03, 0.03, 0.0);
    const int centre = 3 * 7 + 3;
    ASSERT_LT(mesh.nodes[centre].norm(), 1e-12);
    const int up = mesh.add_node(Vec3(0, 0, 0.02)), down = mesh.add_node(Vec3(0, 0, -0.02));
    ExplicitModel model(mesh);
    model.add_shells("patch", ElasticMaterial::make("steel", 210e9, 0.28, 7700), {.thickness = 1e-3});
    model.add_point_mass("masses", up, 2e-3);
    model.add_point_mass("masses", down, 2e-3);
    model.add_force_provider(std::make_unique<OffsetTie>("tie", std::vector<int>{up, down}, std::vector<int>{centre, centre}));
    const Vec3 omega = 100.0 * Vec3(0.6, 0.8, 0.0);
    model.set_initial_velocity([&](const Vec3& X) { return Vec3(omega.cross(X)); });
    std::vector<int> plate(mesh.node_count() - 2);
    for (int i = 0; i < mesh.node_count() - 2; ++i) plate[i] = i;
    model.set_initial_angular_velocity(plate, omega);
    const auto spin = test::run_rigid_spin(model, mesh, omega, 0.25 * 2 * std::numbers::pi / omega.norm());
    std::printf("tied spin: position error %.3e m, max IE/KE %.3e, energy error %.2e, %ld steps\n", spin.position_error,
                spin.max_internal_over_kinetic, spin.summary.energy.relative_error(), spin.summary.steps);
    EXPECT_LT(spin.position_error, 1e-4 * 0.06);
    EXPECT_LT(spin.summary.energy.relative_error(), 1e-4);
}

TEST(OffsetTie, BadInputNamesTheTie) {
    EXPECT_THROW(OffsetTie("t", {1, 2}, {3}), InputError);
    EXPECT_THROW(OffsetTie("t", {1}, {1}), InputError);
    EXPECT_THROW(OffsetTie("t", {}, {}), InputError);
    // An anchor without rotations cannot carry an offset.
    Mesh mesh = box_hex8(0.01, 0.01, 0.01, 1, 1, 1, "box");
    const int free = mesh.add_node(Vec3(0, 0, 0.05));
    ExplicitModel model(mesh);
    model.add_hex8("box", ElasticMaterial::make("steel", 210e9, 0.28, 7700));
    model.add_point_mass("m", free, 1e-3);
    model.add_force_provider(std::make_unique<OffsetTie>("paw tie", std::vector<int>{free}, std::vector<int>{0}));
    EXPECT_THROW(ExplicitSolver(model, test::quiet(1e-5)).run(), InputError);
}
