// The chicken of thesis Chapter 5 (mesh/chicken.hpp): geometry against Table 5-1 and 5-6, exact
// mass properties against closed forms, the meshes (volume, node sets, symmetry), bad input.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/units.hpp"
#include "mesh/chicken.hpp"
#include "mesh/finger.hpp"

using namespace fem;
using units::deg;
using units::mm;
using std::numbers::pi;

namespace {
// Coarse meshes: these tests check the construction, not the discretisation. (const, not constexpr:
// MeshOptions holds a std::string, which clang 14 with libstdc++ 12 does not take in a constant.)
const chicken::MeshOptions kCoarse{.body_size = 25e-3, .leg_size = 6e-3, .order = 2, .half = true};
}  // namespace

TEST(Chicken, Table51ChainAndPlacement) {
    const chicken::Chicken c = chicken::table_5_1_chicken();
    ASSERT_EQ(c.leg.limb_count(), 3);
    EXPECT_NEAR(c.leg.limb_length(0) / mm, 75.373, 1e-3);
    EXPECT_NEAR(c.leg.limb_angle(1) / deg, 147.742, 1e-3);
    // Turned by theta_b = 7.8 degrees, J1 lands on Table 5-6's perch top centre (-15, -71) mm from
    // the centroid (to the mm the table prints).
    Mesh m;
    m.add_node(Vec3(c.leg.joints[0].x(), c.leg.joints[0].y(), 0.0));
    m.add_node(c.head_center());
    m.add_node(Vec3::Zero());
    chicken::place(m, Vec3(0.402, 0.032, 0.184), 7.8 * deg);
    EXPECT_NEAR(m.nodes[0].x(), 0.387, 1e-3);
    EXPECT_NEAR(m.nodes[0].y(), -0.039, 1.0e-3);
    EXPECT_NEAR(chicken::theta_b(m.nodes[1], m.nodes[2]) / deg, 7.8, 1e-12);
    EXPECT_NEAR(m.nodes[2].z(), 0.184, 1e-15);
}

TEST(Chicken, Table53ChainFollowsItsAngles) {
    const chicken::Chicken c = chicken::table_5_3_chicken();
    ASSERT_EQ(c.leg.limb_count(), 2);
    EXPECT_NEAR(c.leg.limb_length(0) / mm, 75.0, 1e-9);
    EXPECT_NEAR(c.leg.limb_length(1) / mm, 70.0, 1e-9);
    EXPECT_NEAR(c.leg.limb_angle(0) / deg, 14.0, 1e-9);
    // Included angle at J2 = theta2 = 35 degrees.
    EXPECT_NEAR(std::remainder(c.leg.limb_angle(0) + pi - c.leg.limb_angle(1), 2 * pi) / deg, 35.0, 1e-9);
}

TEST(Chicken, MassPropertiesAreExactAndSymmetric) {
    const chicken::Chicken c = chicken::table_5_1_chicken();
    const chicken::MassProperties full = chicken::mass_properties(c, false), half = chicken::mass_properties(c, true);
    // OpenCASCADE integrates the B-spline ellipsoid numerically: ~1e-3 relative.
    EXPECT_NEAR(half.volume, 0.5 * full.volume, 2e-3 * full.volume);
    EXPECT_NEAR(full.centroid.z(), 0.0, 1e-6);
    EXPECT_NEAR(full.inertia(0, 2), 0.0, 1e-4 * full.inertia(2, 2));
    // The body ellipsoid dominates: volume within 5 % of 4/3 pi a b c, I_zz within 10 % of its
    // V (a^2 + b^2) / 5 (head, neck, legs and the leg grooves make the rest).
    const double ellipsoid = 4.0 / 3.0 * pi * c.body_a * c.body_b * c.body_c;
    EXPECT_NEAR(full.volume, ellipsoid, 0.05 * ellipsoid);
    EXPECT_NEAR(full.inertia(2, 2), ellipsoid * (c.body_a * c.body_a + c.body_b * c.body_b) / 5.0,
                0.25 * ellipsoid * (c.body_a * c.body_a + c.body_b * c.body_b) / 5.0);
    // A limb is a bar: volume ~ width x depth x length plus its knuckles less the holes.
    const chicken::MassProperties l3 = chicken::limb_mass_properties(c, 3);
    const double bar = c.leg.limbs[2].width * c.leg.limbs[2].depth_lower * c.leg.limb_length(2);
    EXPECT_GT(l3.volume, 0.8 * bar);
    EXPECT_LT(l3.volume, 1.3 * bar);
    EXPECT_NEAR(chicken::density_for_mass(c) * full.volume, 1.69, 1e-12);
}

TEST(Chicken, HalfMeshVolumeAndNodeSets) {
    const chicken::Chicken c = chicken::table_5_1_chicken();
    const Mesh m = chicken::chicken_mesh(c, kCoarse);
    const auto q = finger::mesh_quality(m);
    const double exact = chicken::volume(c, true);
    EXPECT_NEAR(q.volume, exact, 5e-3 * exact);  // tet10 with mid-edge nodes on the true surface
    EXPECT_GT(q.min_scaled_jacobian, 0.0);
    ASSERT_EQ(m.node_set("body_center").size(), 1u);
    EXPECT_LT(m.nodes[m.node_set("body_center")[0]].norm(), 1e-9);
    EXPECT_LT((m.nodes[m.node_set("head")[0]] - c.head_center()).norm(), 1e-9);
    for (int n : m.node_set("symmetry")) EXPECT_NEAR(m.nodes[n].z(), 0.0, 1e-9);
    for (const Vec3& x : m.nodes) EXPECT_GT(x.z(), -1e-9);
    // The paw face: the plane through J1 normal to L1, within the bar.
    const Vec3 j1(c.leg.joints[0].x(), c.leg.joints[0].y(), c.leg.plane_z());
    const double a = c.leg.limb_angle(0);
    ASSERT_GE(m.node_set("paw").size(), 6u);
    for (int n : m.node_set("paw")) EXPECT_NEAR((m.nodes[n] - j1).dot(Vec3(std::cos(a), std::sin(a), 0.0)), 0.0, 1e-6);
}

TEST(Chicken, LimbMeshHoldsAndLoadsItsJoints) {
    const chicken::Chicken c = chicken::table_5_1_chicken();
    const Mesh m = chicken::limb_mesh(c, 2, {.size = 6e-3});
    // Limb 2 runs J2 - J3, both hinges: held through the hole at J3, loaded through the hole at J2.
    for (int n : m.node_set("fixed"))
        EXPECT_NEAR((m.nodes[n] - c.leg.joints[2]).head<2>().norm(), c.leg.hinges[1].hole_radius, 1e-6);
    for (int n : m.node_set("loaded"))
        EXPECT_NEAR((m.nodes[n] - c.leg.joints[1]).head<2>().norm(), c.leg.hinges[0].hole_radius, 1e-6);
    EXPECT_GE(m.node_set("fixed").size(), 10u);
    EXPECT_GE(m.node_set("loaded").size(), 10u);
}

TEST(Chicken, BadInputNamesTheField) {
    chicken::Chicken c = chicken::table_5_1_chicken();
    c.leg.limbs[1].width = 0.0;
    EXPECT_THROW(chicken::validate(c), InputError);
    c = chicken::table_5_1_chicken();
    c.leg.hinges.pop_back();
    EXPECT_THROW(chicken::validate(c), InputError);
    c = chicken::table_5_1_chicken();
    c.length = 150e-3;  // the head would sit inside the body, behind the neck's root
    EXPECT_THROW(chicken::validate(c), InputError);
    EXPECT_THROW(chicken::limb_mesh(chicken::table_5_1_chicken(), 4, {}), InputError);
    try {
        c = chicken::table_5_1_chicken();
        c.leg.limbs[0].depth_lower = 100e-3;  // crosses the symmetry plane
        chicken::validate(c);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("L1"), std::string::npos) << e.what();
    }
}

// The full Table 5-3 bird at Step 1's sizes (15 mm body, 5 mm leg) has no sliver from
// near-coincident features (table_5_3_chicken: the cross brick, the J2 knuckle's depth, the bricks'
// thicknesses). Before those changes: smallest scaled Jacobian 0.002, smallest altitude 0.005 mm
// (an explicit step of 1.6e-8 s); after: 0.068 and 0.46 mm. The task's target, 0.1, is not
// reached: the worst elements left lie where the 1 mm groove's floor and walls meet the hip
// bricks and the body's curved surface (study README, Step 4).
TEST(Chicken, Table53FullMeshHasNoSlivers) {
    const chicken::Chicken c = chicken::table_5_3_chicken();
    const Mesh m = chicken::chicken_mesh(c, {.body_size = 15e-3, .leg_size = 5e-3, .order = 2, .half = false});
    const auto q = finger::mesh_quality(m);
    EXPECT_GE(q.min_scaled_jacobian, 0.05);
    EXPECT_GE(q.min_characteristic_length, 0.4e-3);
}
