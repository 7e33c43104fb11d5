// The hand of thesis Ch 4 (lib/hand) and the ellipsoid mesher (lib/mesh/ellipsoid): Table 4-1/4-2
// counts, the finger placement of the reconstructed frame, the half football's mass and symmetry
// set, the speed schedule, and a short explicit run of the whole scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <filesystem>
#include <set>

#include <fmt/format.h>
#include <unistd.h>

#include "core/error.hpp"
#include "hand/ellipsoid.hpp"
#include "hand/football.hpp"
#include "hand/scene.hpp"
#include "mesh/ellipsoid.hpp"
#include "mesh/finger.hpp"

using namespace fem;
using namespace fem::hand;
using units::deg;
using units::inch;
using units::mm;

namespace {
// Options of a short test run: to end_time, quiet.
ExplicitOptions quiet_run(double end_time) {
    ExplicitOptions opt;
    opt.end_time = end_time;
    opt.print_summary = false;
    opt.progress = false;
    return opt;
}
}  // namespace

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
    const Mat3 R = m.pose(3.0).R;  // one revolution in 3 s: back where it started
    EXPECT_NEAR((R - Mat3::Identity()).norm(), 0.0, 1e-3);
    EXPECT_NEAR(std::acos(std::clamp(0.5 * (m.pose(0.75).R.trace() - 1.0), -1.0, 1.0)), 0.5 * std::numbers::pi, 1e-3);
}

TEST(Hand, PalletFollowsTable44Schedule) {
    // Case 4: 18 in/s, 10 in/s from 1.19 s; the pallet (a rigid part) is where the schedule's exact
    // integral puts it.
    const auto c4 = football::table_4_4()[3];
    HandModel hm(football::scene(c4));
    const double x0 = hm.plate_centre("pallet", 0.0).x();
    EXPECT_NEAR(x0 - hm.plate_centre("pallet", 3.0).x(), football::fast * 1.19 + football::slow * 1.81, 1e-12);
    // The same scene seen from t0 = 0.7 s: the pallet already moved, the switch at model time 0.49 s.
    HandModel hl(seen_from(football::scene(c4), 0.7));
    EXPECT_NEAR(hl.plate_centre("pallet", 3.0 - 0.7).x(), hm.plate_centre("pallet", 3.0).x(), 1e-12);
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
    const Mesh m = drum_mesh(stepped_drum(), 24);
    const auto r = contact::ContactSurface::rigid_part(m, "drum", 0.01);
    ASSERT_EQ(r.segments.size(), 48u);
    for (const auto& s : r.segments) {
        const auto& x = m.nodes;
        const Vec3 c = 0.25 * (x[s.n[0]] + x[s.n[1]] + x[s.n[2]] + x[s.n[3]]);
        const Vec3 n = (x[s.n[1]] - x[s.n[0]]).cross(x[s.n[3]] - x[s.n[0]]);
        EXPECT_GT(n.dot(Vec3(c.x(), 0, c.z())), 0.0);  // the quad's normal points away from the axis
    }
}

TEST(Hand, HalfFootballCutFaceIsNoContactSurface) {
    // The cut face (z = 184 mm, the symmetry plane) is where the mirrored half is: no wall there.
    HandModel hm(football::scene(football::table_4_4()[0]));
    const auto& sym = hm.mesh().node_set("symmetry-football");
    const std::set<int> on(sym.begin(), sym.end());
    const auto& ball = hm.contact("fingers on football").master_surface();
    for (const auto& s : ball.segments) {
        int n_on = 0;
        for (int a = 0; a < s.count; ++a) n_on += on.count(s.n[a]);
        EXPECT_LT(n_on, s.count);
    }
    auto full = contact::ContactSurface::from_part(hm.mesh(), "football", hm.scene().objects[0].material);
    const std::size_t all = full.segments.size();
    EXPECT_EQ(full.remove_faces_on(sym), all - ball.segments.size());
    EXPECT_GT(all - ball.segments.size(), 0u);
    EXPECT_EQ(full.nodes, ball.nodes);
}

// A scene of the hand alone, spinning at the drum's speed from t = 0: with co-rotating damping the
// fingers feel no drag and keep the rigid rotation; with absolute damping they start to trail.
TEST(Hand, CoRotatingDampingDoesNotDragARigidSpin) {
    auto tip_lag = [](DampingFrame frame) {
        Scene s;
        s.hand.fingers = {table_4_1()[3]};  // finger D only
        s.damping_frame = frame;
        HandModel hm(s);
        ExplicitOptions opt = quiet_run(2e-3);
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

TEST(Hand, EllipsoidGraspStopsAtHalfTurnAndFlipTurnsTheHand) {
    // Sec 4.4: the drum stops at 180 deg at 1.5 s; the flip turns the whole hand 135 deg about +z in
    // 0.5 s from 2 s (compose(turn, spin)); the object is carried to the drum centre by 1.5 s.
    HandModel hm(ellipsoid::scene());
    const RigidMotion& m = hm.drum_motion();
    const Vec3 p(0.1, 0.05, 0.0);
    const Vec3 half = m.position(p, 1.5);     // spin: pi about -y (a half turn), no flip yet
    EXPECT_NEAR((half - Vec3(-0.1, 0.05, 0.0)).norm(), 0.0, 1e-9);
    EXPECT_NEAR((m.position(p, 2.0) - half).norm(), 0.0, 1e-12);  // held between 1.5 and 2 s
    const double a = ellipsoid::flip_speed * ellipsoid::flip_duration;  // 2.355 rad = 134.9 deg
    const Vec3 flipped = m.position(p, 2.5);
    const Vec3 expect(std::cos(a) * half.x() - std::sin(a) * half.y(), std::sin(a) * half.x() + std::cos(a) * half.y(), half.z());
    EXPECT_NEAR((flipped - expect).norm(), 0.0, 1e-9);
    EXPECT_NEAR((m.position(p, 3.0) - flipped).norm(), 0.0, 1e-12);  // stopped after 0.5 s
    EXPECT_NEAR(m.angular_velocity(2.25).z(), ellipsoid::flip_speed, 1e-12);
    // The object reaches x = 0 when the drum stops: its start is the conveyor's travel in that time.
    EXPECT_NEAR(ellipsoid::centre().x() - ellipsoid::conveyor * ellipsoid::spin_stop(), 0.0, 1e-15);
    // The same scene from t0 = 1.0 s: the hand turned by omega t0, motions shifted.
    HandModel hl(seen_from(ellipsoid::scene(), 1.0));
    const Mat3 R_later = hl.drum_motion().pose(1.0).R;  // model time 1.0 = 2.0 s: turned by omega (1.5 s - 1.0 s)
    const double turned = std::acos(std::clamp(0.5 * (R_later.trace() - 1.0), -1.0, 1.0));
    EXPECT_NEAR(turned, ellipsoid::drum_speed * (ellipsoid::spin_stop() - 1.0), 1e-9);
    EXPECT_NEAR(hl.scene().hand.drum.initial_angle, ellipsoid::drum_speed * 1.0, 1e-15);
    EXPECT_NEAR(hl.scene().objects[0].centre.x(), ellipsoid::centre().x() - ellipsoid::conveyor * 1.0, 1e-15);
    // Grasp: the object's x-velocity is prescribed; flip: free.
    EXPECT_NE(ellipsoid::scene().objects[0].carried_velocity.x(), 0.0);
    ellipsoid::Options flip;
    flip.phase = ellipsoid::Phase::flip;
    EXPECT_EQ(ellipsoid::scene(flip).objects[0].carried_velocity.norm(), 0.0);
}

// The flip restarts from the grasp's dump with the flip's scene (object no longer carried): core's
// restart accepts the changed prescriptions, and the object is then free in x.
TEST(Hand, FlipSceneRestartsFromAGraspDump) {
    const auto dir = std::filesystem::temp_directory_path() / fmt::format("hand-flip-restart-{}", ::getpid());
    ellipsoid::Options g;
    HandModel grasp(seen_from(ellipsoid::scene(g), 1.0));
    ExplicitOptions opt;
    opt.end_time = 4e-4;
    opt.print_summary = false;
    opt.progress = false;
    opt.restart_dir = dir;
    opt.restart_times = {2e-4};
    opt.name = "grasp";
    ExplicitSolver gs(grasp.model(), opt);
    gs.run();
    ASSERT_EQ(gs.restart_files().size(), 1u);
    ellipsoid::Options f = g;
    f.phase = ellipsoid::Phase::flip;
    HandModel flip(seen_from(ellipsoid::scene(f), 1.0));
    ExplicitOptions fopt = opt;
    fopt.restart_times.clear();
    fopt.restart_from = gs.restart_files().front();
    fopt.name = "flip";
    ExplicitSolver fs(flip.model(), fopt);
    fs.run();
    EXPECT_NEAR(fs.time(), gs.time(), 1e-5);
    // Both carried at -18 in/s so far (the flip's object keeps its velocity: nothing pushes it yet).
    const int n = flip.part_nodes("ellipsoid")[0];
    EXPECT_NEAR(fs.state().v[n].x(), -ellipsoid::conveyor, 1e-6);
    std::filesystem::remove_all(dir);
}

// seen_from(scene, t0): drum turned by its speed's integral, objects and plates moved, curves
// shifted; a hand that has turned before t0 cannot be skipped to t0.
TEST(Hand, SeenFromMovesTheSceneToT0) {
    const Scene s = football::scene(football::table_4_4()[3]);
    const Scene l = seen_from(s, 0.5);
    EXPECT_DOUBLE_EQ(l.hand.drum.initial_angle, s.hand.drum.omega(0.0) * 0.5);
    EXPECT_DOUBLE_EQ(l.objects[0].centre.x(), s.objects[0].centre.x() - football::fast * 0.5);
    EXPECT_DOUBLE_EQ(l.plates[0].centre.x(), s.plates[0].centre.x() - football::fast * 0.5);
    EXPECT_EQ(l.plates[0].speed(1.19 - 0.5), football::slow);
    Scene turned = s;
    turned.turn.omega = Curve::constant(1.0);
    EXPECT_THROW(seen_from(turned, 0.5), InputError);
    Scene carried = ellipsoid::scene();
    EXPECT_NO_THROW(seen_from(carried, 1.0));
    EXPECT_THROW(seen_from(carried, 1.6), InputError);  // the carriage stopped at 1.5 s
}

namespace {
// The run summary's record of contact pair `name`.
const InterfaceSummary& interface(const RunSummary& sum, const std::string& name) {
    std::string names;
    for (const auto& c : sum.interfaces) {
        if (c.name == name) return c;
        names += " '" + c.name + "'";
    }
    throw InputError("no contact interface " + name + "; there are" + names);
}
}  // namespace

// Finger against finger (a [[contact]] pair of two fingers, CASE_FILE.md): two 3-inch fingers side by
// side on a stopped drum, finger B swung towards A about the drum axis (its roots held). With the
// pair the fingers stay apart (penetration below 0.2 of the element, the studies' limit); with the
// same pair at a penalty 1e-6 of it (no force, the same measure of penetration) B passes into A.
TEST(Hand, FingerPairContactKeepsPressedFingersApart) {
    auto run = [](double penalty_scale) {
        Scene s;
        FingerRow a = table_4_1()[3];  // finger D's row: 3 in, no roll or pitch
        a.alpha = 0.0;                 // undamped: B keeps its swing
        FingerRow b = a;
        a.name = "A", b.name = "B";
        b.initial_angle = a.initial_angle + 10.0 * deg;
        s.hand.fingers = {a, b};
        s.hand.drum = stepped_drum(0.0);
        s.contacts.push_back({"finger-B", "finger-A", {}, true, penalty_scale});
        HandModel hm(s);
        // B turned towards A about the drum axis at 15 rad/s (tip ~2.8 m/s).
        const auto& X = hm.mesh().nodes;
        Vec3 ca = Vec3::Zero(), cb = Vec3::Zero();
        for (int n : hm.part_nodes("finger-A")) ca += X[n] / hm.part_nodes("finger-A").size();
        for (int n : hm.part_nodes("finger-B")) cb += X[n] / hm.part_nodes("finger-B").size();
        const Vec3 c = s.hand.drum.centre;
        Vec3 w = 15.0 * Vec3::UnitY();
        if (w.cross(cb - c).dot(ca - cb) < 0) w = -w;
        for (int n : hm.part_nodes("finger-B")) hm.model().set_initial_velocity({n}, w.cross(X[n] - c));
        double gap = 1e9;
        for (int i : hm.part_nodes("finger-A"))
            for (int j : hm.part_nodes("finger-B")) gap = std::min(gap, (X[i] - X[j]).norm());
        fmt::print("fingers A and B: closest nodes {:.2f} mm apart at the start\n", 1e3 * gap);
        ExplicitOptions opt = quiet_run(12e-3);
        ExplicitSolver solver(hm.model(), opt);
        return solver.run();
    };
    const RunSummary held = run(0.1), free = run(1e-6);
    const auto& h = interface(held, "finger-B on finger-A");
    const auto& f = interface(free, "finger-B on finger-A");
    fmt::print("finger B against finger A: penetration {:.3f} of the element with contact, {:.3f} without; contact energy {:.3g} J\n",
               h.max_penetration_fraction, f.max_penetration_fraction, h.energy);
    EXPECT_GT(h.max_penetration_fraction, 0.0);    // they touched
    EXPECT_LT(h.max_penetration_fraction, 0.2);    // and did not interpenetrate
    EXPECT_GT(f.max_penetration_fraction, 0.5);    // without the force B goes into A
}

// Scene::mirror_contact: a finger whose tip sweeps across the symmetry plane of a half object stays
// on its side of it (the frictionless wall "mirror-plane"); without it the tip crosses the plane.
// Only the finger's free nodes are measured: its root nodes ride the prescribed drum motion, which
// no contact can stop. (The first version of this test swept finger D for 10 ms from theta = 0,
// where it points -z and moves tangentially, and took the highest of all its nodes: that was a root
// node carried by the drum, which went as far "through" the wall with it as without it, and the
// wall was withdrawn for that. The wall itself was never at fault.)
TEST(Hand, MirrorContactKeepsFingersOnTheirSideOfTheSymmetryPlane) {
    // Finger D on a drum turning at 10 rad/s, starting 35 deg before it points +z (its tip's
    // highest z); a small half object far away (only its symmetry plane z = plane matters).
    // Returns the summary and the largest z of the finger's free (non-root) nodes over the run.
    auto run = [](double plane, bool mirror, double& zmax, double& z0) {
        Scene s;
        s.hand.fingers = {table_4_1()[3]};
        s.hand.drum = stepped_drum(10.0);
        s.hand.drum.initial_angle = (180.0 - 35.0) * std::numbers::pi / 180.0;
        EllipsoidObject o;
        o.part = "object";
        o.semi_axes = Vec3(20, 20, 20) * mm;
        o.grid = EllipsoidGrid{4, 4, 2, 1, 0.5};
        o.material = ElasticMaterial::make("rubber", 6.1e6, 0.49, 1000.0);
        o.centre = Vec3(1.0, 0.0, plane);
        s.objects.push_back(o);
        s.mirror_contact = mirror;
        HandModel hm(s);
        ExplicitOptions opt = quiet_run(70e-3);  // 40 deg of drum turn: past the top
        opt.observer_interval = 0.0;
        ExplicitSolver solver(hm.model(), opt);
        const auto& root = hm.mesh().node_set("root-D");
        std::vector<int> free;
        for (int n : hm.part_nodes("finger-D"))
            if (std::find(root.begin(), root.end(), n) == root.end()) free.push_back(n);
        zmax = z0 = -1e9;
        for (int n : free) z0 = std::max(z0, hm.mesh().nodes[n].z());
        solver.observer = [&](const ExplicitSolver& sv) {
            for (int n : free) zmax = std::max(zmax, sv.state().x[n].z());
        };
        return solver.run();
    };
    double zfree = 0, z0 = 0;
    run(1.0, false, zfree, z0);
    ASSERT_GT(zfree, 175 * mm);  // the tip (radius ~184 mm) reaches near +z
    // The plane 6 mm below the free tip's highest point: the tip must be pushed back 6 mm.
    const double plane = zfree - 6 * mm;
    double zheld = 0;
    ASSERT_LT(z0, plane - 5 * mm);  // the finger starts well clear of the plane
    const RunSummary held = run(plane, true, zheld, z0);
    const auto& wall = interface(held, "fingers on mirror-plane");
    fmt::print("finger D beyond its mirror plane: {:.2f} mm free, {:.3f} mm with the wall ({:.3f} of the element)\n",
               1e3 * (zfree - plane), 1e3 * (zheld - plane), wall.max_penetration_fraction);
    EXPECT_GT(wall.max_penetration_fraction, 0.0);  // it touched
    EXPECT_LT(wall.max_penetration_fraction, 0.2);  // and stayed on its side
    EXPECT_LT(zheld - plane, 1 * mm);
}

// A mesh object in a hand scene (Scene::meshes; the chicken of Ch 5 is one): a half tet10 block,
// its bottom face tied to a plate moving on a two-segment path (RigidMotion::piecewise_translation,
// the perch of Table 5-6 in miniature) until a release time, when gravity comes on. Written before
// the first run: held, the tied nodes follow the plate within 0.1 mm; released, nothing but gravity
// and the symmetry plane (along z) acts on it, so its momentum grows by M g per second in x and y
// (within 1e-3 of g, between two times after the release); tied, it would not (gravity is off until
// then and the plate moves at a constant velocity). Bad input is refused naming the culprit.
TEST(Hand, MeshObjectTiedToAPlateOnAPathLetsGoAtTheReleaseTime) {
    const double plane = 0.184, t_corner = 0.005, t_release = 0.010, t_end = 0.020;
    const Vec3 v1(-0.4723, 0.04132, 0), v2(-0.4105, -0.23705, 0), g(0, -9.81, 0);
    auto scene = [&] {
        Scene s;
        s.hand.fingers = {table_4_1()[3]};  // finger D only, far from the block
        MeshObject o;
        o.part = "block";
        o.mesh = box_tets(0.03, 0.02, 0.01, 3, 2, 1, ElementShape::Tet10, "block");
        o.mesh.translate(Vec3(1.0, 0.0, plane - 0.01));  // its face z1 on the symmetry plane
        o.material = ElasticMaterial::make("rubber", 6.1e6, 0.49, 1000.0);
        o.initial_velocity = v1;
        o.symmetry_set = "z1";
        o.ties = {{.node_set = "y0", .plate = "perch", .options = {.release_time = t_release}}};
        s.meshes.push_back(o);
        Plate perch;
        perch.part = "perch";
        perch.centre = Vec3(1.015, 0.0, plane - 0.005);
        perch.u = 0.03 * Vec3::UnitX(), perch.v = -0.01 * Vec3::UnitZ();
        perch.path = RigidMotion::piecewise_translation({{0.0, v1}, {t_corner, v2}}, "perch");
        s.plates.push_back(perch);
        s.gravity = g;
        s.gravity_curve = Curve::step(t_release);
        return s;
    };
    HandModel hm(scene());
    const auto& bottom = hm.mesh().node_set("y0-block");
    const auto nodes = hm.part_nodes("block");
    const OffsetTie& tie = hm.tie("block", "perch");
    ExplicitOptions opt = quiet_run(t_end);
    opt.observer_interval = 0.0;
    ExplicitSolver solver(hm.model(), opt);
    const RigidMotion path = *hm.scene().plates[0].path;
    double held_gap = 0.0, ta = 0.0, tb = 0.0;
    Vec3 pa = Vec3::Zero(), pb = Vec3::Zero();
    double mass = 0.0;
    solver.observer = [&](const ExplicitSolver& sv) {
        const NodalState& st = sv.state();
        const double t = sv.time();
        if (t < t_release)
            for (int n : bottom) held_gap = std::max(held_gap, (st.x[n] - path.position(st.X[n], t)).norm());
        Vec3 p = Vec3::Zero();
        mass = 0.0;
        for (int n : nodes) p += st.mass[n] * st.v[n], mass += st.mass[n];
        if (t >= t_release + 0.002 && ta == 0.0) ta = t, pa = p;
        tb = t, pb = p;
    };
    const RunSummary summary = solver.run();
    const Vec3 a = (pb - pa) / (mass * (tb - ta));
    fmt::print("block on perch: held gap {:.3e} m, after release a = ({:.4f}, {:.4f}) m/s2, energy error {:.2e}\n", held_gap,
               a.x(), a.y(), summary.energy.relative_error());
    EXPECT_LT(held_gap, 1e-4);
    EXPECT_NEAR(a.x(), 0.0, 1e-3 * 9.81);
    EXPECT_NEAR(a.y(), g.y(), 1e-3 * 9.81);
    EXPECT_TRUE(tie.released(t_end));
    EXPECT_LT(summary.energy.relative_error(), 1e-3);

    // Bad input.
    Scene bad = scene();
    bad.meshes[0].ties[0].plate = "shackle";
    auto error_of = [](const Scene& sc) -> std::string {
        try {
            HandModel m(sc);
        } catch (const InputError& e) {
            return e.what();
        }
        return "no error";
    };
    EXPECT_NE(error_of(bad).find("plate 'shackle'"), std::string::npos);
    bad = scene();
    bad.meshes[0].symmetry_set = "x0";  // a face x = const, not z = const
    EXPECT_THROW(HandModel m(bad), InputError);
    bad = scene();
    bad.meshes[0].mesh.node_sets["none"] = {};
    bad.meshes[0].symmetry_set = "none";  // an empty cut: named, not read past its end
    EXPECT_NE(error_of(bad).find("symmetry set 'none' of 'block' has no nodes"), std::string::npos);
    EXPECT_THROW(seen_from(scene(), 0.001), InputError);  // not written for mesh objects
}
