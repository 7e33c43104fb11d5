// The hand of thesis Ch 4 (lib/hand) and the ellipsoid mesher (lib/mesh/ellipsoid): Table 4-1/4-2
// counts, the finger placement of the reconstructed frame, the half football's mass and symmetry
// set, the speed schedule, and a short explicit run of the whole scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "hand/scene.hpp"
#include "mesh/ellipsoid.hpp"
#include "mesh/finger.hpp"

using namespace fem;
using namespace fem::hand;
using units::deg;
using units::inch;
using units::mm;

TEST(Ellipsoid, HalfFootballCountsAndVolume) {
    // Table 4-2: the half football has 512 elements and 677 nodes; our O-grid 512 / 678.
    const Mesh m = hex_ellipsoid(Vec3(122, 66, 66) * mm, EllipsoidGrid{}, true, "football");
    EXPECT_EQ(m.element_count(), 512);
    EXPECT_EQ(m.node_count(), 678);
    const double exact = 2.0 / 3.0 * std::numbers::pi * 122 * 66 * 66 * 1e-9;  // half ellipsoid
    const double v = finger::mesh_quality(m).volume;
    EXPECT_NEAR(v / exact, 1.0, 0.05);   // faceted: a little inside
    EXPECT_LT(v, exact);
    EXPECT_GT(finger::mesh_quality(m).min_scaled_jacobian, 0.3);
    for (int n : m.node_set("symmetry")) EXPECT_EQ(m.nodes[n].z(), 0.0);
    for (const auto& p : m.nodes) EXPECT_LE(p.z(), 0.0);
    for (int n : m.node_set("surface")) {
        const Vec3 p = m.nodes[n].cwiseQuotient(Vec3(122, 66, 66) * mm);
        EXPECT_NEAR(p.norm(), 1.0, 1e-12);
    }
    EXPECT_EQ(m.nodes[m.node_set("centre")[0]].norm(), 0.0);
}

TEST(Ellipsoid, FullIsClosedAndBadInputNamed) {
    const Mesh m = hex_ellipsoid(Vec3(97, 57, 66) * mm, EllipsoidGrid{6, 4, 4, 2, 0.5}, false, "ellipsoid");
    EXPECT_NEAR(finger::mesh_quality(m).volume / (4.0 / 3.0 * std::numbers::pi * 97 * 57 * 66 * 1e-9), 1.0, 0.06);
    EXPECT_THROW(hex_ellipsoid(Vec3(1, 1, 1), EllipsoidGrid{4, 4, 3, 1, 0.5}, true, "odd"), InputError);
    EXPECT_THROW(hex_ellipsoid(Vec3(1, -1, 1), EllipsoidGrid{}, true, "neg"), InputError);
}

TEST(Hand, Table42CountsPerFinger) {
    const Mesh m = hand_mesh(HandSpec{});
    int elements = 0;
    for (const auto& b : m.blocks) {
        const bool upper = b.part == "finger-A" || b.part == "finger-B";
        EXPECT_EQ(b.size(), upper ? 725 : 500) << b.part;
        elements += b.size();
    }
    EXPECT_EQ(elements, 2 * 725 + 3 * 500);
    EXPECT_EQ(m.node_count(), 2 * 1080 + 3 * 756);
}

TEST(Hand, PlacementFollowsTable41) {
    const HandSpec h;
    for (const auto& f : h.fingers) {
        const Placement p = place_finger(h, f);
        // Root on the drum at r_drum, h_f; the finger axis pitched by R_z out of the horizontal.
        EXPECT_NEAR(std::hypot(p.root.x(), p.root.z()), f.drum_radius, 1e-12) << f.name;
        EXPECT_NEAR(p.root.y(), f.root_height, 1e-12) << f.name;
        EXPECT_NEAR(std::asin(p.axis().y()), f.pitch, 1e-12) << f.name;
        // The axis stays in the radial-vertical plane (pitch about the tangential direction).
        const Vec3 er(std::sin(p.angle), 0, -std::cos(p.angle));
        EXPECT_NEAR(p.axis().dot(er), std::cos(f.pitch), 1e-12) << f.name;
        EXPECT_NEAR((p.rotation.transpose() * p.rotation - Mat3::Identity()).norm(), 0.0, 1e-12);
        EXPECT_NEAR(p.rotation.determinant(), 1.0, 1e-12);
        // Roll: the major axis (mesh x) makes angle R_x with the vertical plane's y' before the pitch.
        const Vec3 major = p.rotation.col(0);
        const Vec3 et(std::cos(p.angle), 0, std::sin(p.angle));
        EXPECT_NEAR(std::atan2(major.dot(et), std::hypot(major.dot(er), major.y())), f.roll, 1e-9) << f.name;
    }
    // Finger D at theta_f = 0 points along -z at t = 0; A (theta_f -11.25 deg) is ahead of it in the
    // rotation (phi = +11.25 deg, tip towards +x), B behind.
    const auto rows = table_4_1();
    EXPECT_NEAR(place_finger(h, rows[3]).axis().z(), -std::cos(10 * deg), 1e-12);
    EXPECT_GT(place_finger(h, rows[0]).axis().x(), 0.0);
    EXPECT_LT(place_finger(h, rows[1]).axis().x(), 0.0);
    // The mirror case flips the roll only.
    HandSpec mirror;
    mirror.roll_sign = -1;
    EXPECT_NEAR((place_finger(mirror, rows[3]).rotation - place_finger(h, rows[3]).rotation).norm(), 0.0, 1e-12);
    EXPECT_GT((place_finger(mirror, rows[0]).rotation - place_finger(h, rows[0]).rotation).norm(), 0.1);
}

TEST(Hand, DrumCarriesObjectSideFingersWithTheFlow) {
    const Drum d = stepped_drum();
    const auto m = d.motion();
    // A point on +z moves in -x; one revolution in 3 s (Table 4-3).
    EXPECT_LT(m.velocity(Vec3(0, 0, 0.1), 0.0).x(), 0.0);
    EXPECT_NEAR(m.angle(3.0), 2 * std::numbers::pi, 1e-3);
}

TEST(Hand, SpeedScheduleStepsAndIntegral) {
    const auto f = speed_schedule({{0.0, 0.457}, {1.19, 0.254}});
    EXPECT_DOUBLE_EQ(f(1.0), 0.457);
    EXPECT_DOUBLE_EQ(f(2.0), 0.254);
    EXPECT_NEAR(f.integral(3.0), 0.457 * 1.19 + 0.254 * 1.81, 1e-9);
    EXPECT_THROW(speed_schedule({{1.0, 1.0}, {0.5, 2.0}}), InputError);
}

TEST(Hand, MergedSurfaceKeepsEveryFingersFacesAndNodes) {
    const Mesh m = hand_mesh(HandSpec{});
    const auto rubber = finger::rubber();
    std::vector<contact::ContactSurface> each;
    std::size_t segments = 0, nodes = 0;
    for (const char* f : {"A", "B", "C", "D", "E"}) {
        each.push_back(contact::ContactSurface::from_part(m, std::string("finger-") + f, rubber));
        segments += each.back().segments.size(), nodes += each.back().nodes.size();
    }
    const auto merged = contact::ContactSurface::merge("fingers", each);
    EXPECT_EQ(merged.segments.size(), segments);
    EXPECT_EQ(merged.nodes.size(), nodes);
    EXPECT_TRUE(std::is_sorted(merged.nodes.begin(), merged.nodes.end()));
    EXPECT_THROW(contact::ContactSurface::merge("twice", {each[0], each[0]}), InputError);
}

TEST(Hand, DrumSurfaceFacesOutward) {
    const auto r = drum_surface(stepped_drum(), 24, 0.01);
    ASSERT_EQ(r.surface.segments.size(), 48u);
    for (const auto& s : r.surface.segments) {
        const Vec3 c = 0.25 * (r.points[s.n[0]] + r.points[s.n[1]] + r.points[s.n[2]] + r.points[s.n[3]]);
        const Vec3 n = (r.points[s.n[1]] - r.points[s.n[0]]).cross(r.points[s.n[3]] - r.points[s.n[0]]);
        EXPECT_GT(n.dot(Vec3(c.x(), 0, c.z())), 0.0);  // the quad's normal points away from the axis
    }
}

// A scene of the hand alone, spinning at the drum's speed from t = 0: with co-rotating damping the
// fingers feel no drag and keep the rigid rotation; with absolute damping they start to trail.
TEST(Hand, CoRotatingDampingDoesNotDragARigidSpin) {
    auto tip_lag = [](DampingFrame frame) {
        Scene s;
        s.hand.fingers = {table_4_1()[3]};  // finger D only
        s.damping_frame = frame;
        HandModel hm(s);
        ExplicitOptions opt;
        opt.end_time = 2e-3;
        opt.print_summary = false;
        opt.progress = false;
        ExplicitSolver solver(hm.model(), opt);
        solver.run();
        const int n = hm.tip_node("D");
        const Vec3 rigid = hm.drum_position(solver.state().X[n], solver.time());
        return -(solver.state().x[n] - rigid).dot(hm.drum_motion().velocity_at(rigid, solver.time()).normalized());
    };
    const double absolute = tip_lag(DampingFrame::absolute), corotating = tip_lag(DampingFrame::drum);
    EXPECT_GT(absolute, 1e-5);                     // trails: alpha m v drag
    EXPECT_LT(std::abs(corotating), 0.05 * absolute);  // only the centrifugal stretch's tangential share
}

TEST(Hand, PlateScheduleCanChangeDuringARun) {
    Scene s;
    s.hand.fingers = {table_4_1()[3]};
    Plate p;
    p.part = "pallet";
    p.centre = Vec3(0.5, -0.02, 0.16);
    p.u = Vec3(0.2, 0, 0), p.v = Vec3(0, 0, -0.05);
    p.schedule = {{0.0, 1.0}};
    s.plates.push_back(p);
    HandModel hm(s);
    EXPECT_NEAR(hm.plate_centre("pallet", 1.0).x(), 0.5 - 1.0, 1e-12);
    hm.set_plate_schedule("pallet", {{0.0, 1.0}, {0.5, 0.25}});
    EXPECT_NEAR(hm.plate_centre("pallet", 0.5).x(), 0.5 - 0.5, 1e-6);      // unchanged up to the switch
    EXPECT_NEAR(hm.plate_centre("pallet", 1.0).x(), 0.5 - 0.625, 1e-6);
    EXPECT_THROW(hm.set_plate_schedule("belt", {{0.0, 1.0}}), InputError);
}
