// Nodes tied to a shell node at an offset (explicit/offset_tie.hpp): carried rigidly by the
// anchor's rotation, and bad input refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
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
    EXPECT_THROW(OffsetTie("t", {}, std::vector<int>{}), InputError);
    // An anchor without rotations cannot carry an offset.
    Mesh mesh = box_hex8(0.01, 0.01, 0.01, 1, 1, 1, "box");
    const int free = mesh.add_node(Vec3(0, 0, 0.05));
    ExplicitModel model(mesh);
    model.add_hex8("box", ElasticMaterial::make("steel", 210e9, 0.28, 7700));
    model.add_point_mass("m", free, 1e-3);
    model.add_force_provider(std::make_unique<OffsetTie>("paw tie", std::vector<int>{free}, std::vector<int>{0}));
    EXPECT_THROW(ExplicitSolver(model, test::quiet(1e-5)).run(), InputError);
}

// A paw on its perch (thesis Sec 5.3; THESIS_CH4_5.md reconstruction 14): a 1 g node tied to the
// Table 5-6 perch path (RigidMotion::piecewise_translation, 5 degrees up, the corner at 0.7 s, 30
// degrees down), released at the shackling time 0.9 s when gravity comes on. Written before the
// first run: held, it follows the perch within 5e-5 m (the corner's velocity jump, 0.285 m/s, over
// the tie's angular frequency, 2 pi 2 kHz, is 2.3e-5 m); released, it flies freely: at 1.0 s it is
// where the perch's position and velocity at 0.9 s and gravity put it, within 5e-5 m (the tie, had
// it held, would keep it 49 mm higher), and the tie exerts nothing after the release.
TEST(OffsetTie, TiedToAMotionFollowsThePerchThenLetsGoAtTheReleaseTime) {
    Mesh mesh = box_hex8(0.05, 0.05, 0.05, 1, 1, 1, "box");  // a fixed block: only sets the step
    const Vec3 X(0.387, 0.0, 0.184);
    const int paw = mesh.add_node(X);
    ExplicitModel model(mesh);
    model.add_hex8("box", ElasticMaterial::make("steel", 210e9, 0.28, 7700));
    std::vector<int> box(mesh.node_count() - 1);
    for (int i = 0; i < mesh.node_count() - 1; ++i) box[i] = i;
    model.fix(box, Dofs::all());
    model.add_point_mass("paw", paw, 1e-3);
    const Vec3 v1(-0.4723, 0.04132, 0), v2(-0.4105, -0.23705, 0), g(0, -9.81, 0);
    const double t_release = 0.9, t_end = 1.0;
    const RigidMotion perch = RigidMotion::piecewise_translation({{0.0, v1}, {0.7, v2}}, "perch");
    model.set_initial_velocity({paw}, v1);  // Table 5-6: the bird starts with the conveyor
    model.set_gravity(g, t_release);
    auto& tie = dynamic_cast<OffsetTie&>(model.add_force_provider(
        std::make_unique<OffsetTie>("paw on perch", std::vector<int>{paw}, perch, OffsetTieOptions{.release_time = t_release})));
    ExplicitOptions options = test::quiet(t_end);
    options.observer_interval = 0.0;  // every cycle
    ExplicitSolver solver(model, options);
    double held_gap = 0.0, force_after = 0.0, t_previous = 0.0;
    solver.observer = [&](const ExplicitSolver& s) {
        const double t = s.time();
        if (t < t_release) held_gap = std::max(held_gap, (s.state().x[paw] - perch.position(X, t)).norm());
        // The forces of this cycle were evaluated at the previous cycle's time or later.
        if (tie.released(t_previous)) force_after = std::max(force_after, tie.total_force().norm());
        t_previous = t;
    };
    const RunSummary summary = solver.run();
    const double tau = solver.time() - t_release;
    const Vec3 free_flight = perch.position(X, t_release) + v2 * tau + 0.5 * g * tau * tau;
    const double flight_error = (solver.state().x[paw] - free_flight).norm();
    std::printf("paw on perch: held gap %.3e m, free-flight error %.3e m at %.4f s (held it would be %.1f mm higher), "
                "%ld steps, energy error %.2e\n",
                held_gap, flight_error, solver.time(), 1e3 * (perch.position(X, solver.time()) - free_flight).y(), summary.steps,
                summary.energy.relative_error());
    EXPECT_LT(held_gap, 5e-5);
    EXPECT_LT(flight_error, 5e-5);
    EXPECT_EQ(force_after, 0.0);
    EXPECT_FALSE(tie.released(0.8999));
}

TEST(OffsetTie, MotionTieBadInputNamesTheTie) {
    const RigidMotion m = RigidMotion::translation(Vec3(1, 0, 0));
    EXPECT_NE(test::input_error([&] { OffsetTie("paws", {}, m); }).find("paws"), std::string::npos);
    EXPECT_NE(test::input_error([&] { OffsetTie("paws", {3, 4, 3}, m); }).find("node 3 is listed twice"), std::string::npos);
    EXPECT_NE(test::input_error([&] { OffsetTie("paws", {3}, m, {.release_time = std::nan("")}); }).find("release time"),
              std::string::npos);
}

// The shackle's gripper taking the paws at the shackling time (engage_time): a 1 g paw flying
// freely at 0.4 m/s along x is taken at 0.05 s by a tie to a motion at (-0.4105, -0.23705) m/s (the
// Table 5-6 conveyor after its apex): before that the tie exerts nothing (the paw where its free
// flight puts it, to round-off); from 5 ms after the engagement on the paw rides the motion at the
// point where it was taken (gap below 1 um: the velocity jump of 0.87 m/s sets a transient of
// ~v / omega = 0.07 mm, gone within a few periods at a damping ratio 0.3). A run resumed from a dump
// taken after the engagement ends bit for bit where the uninterrupted one ends: the held points are
// restart state (re-taken at the resume they would hold the paw where the dump left it, and the
// dashpot's transient would differ).
TEST(OffsetTie, EngagedLateHoldsTheNodeWhereItIsThenAndResumesBitForBit) {
    Mesh mesh = box_hex8(0.05, 0.05, 0.05, 1, 1, 1, "box");  // a fixed block: only sets the step
    const Vec3 X(0.3, 0.1, 0.1), v0(0.4, 0.0, 0.0), vm(-0.4105, -0.23705, 0.0);
    const int paw = mesh.add_node(X);
    const double t_engage = 0.05, t_dump = 0.07, t_end = 0.1;
    const RigidMotion gripper = RigidMotion::translation(vm);
    auto model_of = [&] {
        auto m = std::make_unique<ExplicitModel>(mesh);
        m->add_hex8("box", ElasticMaterial::make("steel", 210e9, 0.28, 7700));
        std::vector<int> box(mesh.node_count() - 1);
        for (int i = 0; i < mesh.node_count() - 1; ++i) box[i] = i;
        m->fix(box, Dofs::all());
        m->add_point_mass("paw", paw, 1e-3);
        m->set_initial_velocity({paw}, v0);
        m->add_force_provider(std::make_unique<OffsetTie>("gripper", std::vector<int>{paw}, gripper, OffsetTieOptions{.engage_time = t_engage}));
        return m;
    };
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "fem_offset_tie_engage";
    std::filesystem::remove_all(dir);
    auto whole = model_of();
    ExplicitOptions o = test::quiet(t_end);
    o.observer_interval = 0.0;  // every cycle
    o.name = "gripper";
    o.restart_dir = dir, o.restart_times = {t_dump};
    ExplicitSolver solver(*whole, o);
    double free_error = 0.0, held_gap = 0.0;
    Vec3 taken_at = Vec3::Constant(std::nan(""));
    double t_previous = 0.0, t_taken = 0.0;
    solver.observer = [&](const ExplicitSolver& s) {
        const double t = s.time();
        const Vec3& x = s.state().x[paw];
        if (t <= t_engage) free_error = std::max(free_error, (x - (X + v0 * t)).norm());
        if (t_previous < t_engage && t >= t_engage) taken_at = x, t_taken = t;  // the next cycle's forces take this position
        if (t > t_engage + 5e-3) held_gap = std::max(held_gap, (x - taken_at - vm * (t - t_taken)).norm());
        t_previous = t;
    };
    const RunSummary summary = solver.run();
    std::printf("gripper taking a paw: free-flight error %.2e m, held gap %.2e m after 5 ms, %ld steps, energy error %.2e\n",
                free_error, held_gap, summary.steps, summary.energy.relative_error());
    EXPECT_LT(free_error, 1e-12);
    EXPECT_LT(held_gap, 1e-6);
    ASSERT_EQ(solver.restart_files().size(), 1u);
    auto resumed_model = model_of();
    ExplicitOptions orr = test::quiet(t_end);
    orr.name = "gripper";
    orr.restart_from = solver.restart_files()[0];
    ExplicitSolver resumed(*resumed_model, orr);
    resumed.run();
    EXPECT_EQ(resumed.state().x[paw], solver.state().x[paw]);
    EXPECT_EQ(resumed.state().v[paw], solver.state().v[paw]);
    std::filesystem::remove_all(dir);
}

TEST(OffsetTie, EngageTimeNeedsAMotionAndMustComeBeforeTheRelease) {
    EXPECT_NE(test::input_error([] { OffsetTie("grip", {1}, {2}, {.engage_time = 0.9}); }).find("needs a prescribed motion"),
              std::string::npos);
    const RigidMotion m = RigidMotion::fixed();
    EXPECT_NE(test::input_error([&] { OffsetTie("grip", {3}, m, {.release_time = 0.5, .engage_time = 0.9}); }).find("before the release"),
              std::string::npos);
}
