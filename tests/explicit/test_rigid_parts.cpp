// Rigid parts and nodes tied to rigid motions in the explicit model (ExplicitModel::add_rigid_part,
// prescribe_motion with a RigidMotion).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "core/error.hpp"
#include "explicit_test_support.hpp"

using namespace fem;
using namespace fem::test;
using fem::test::quiet;
namespace fs = std::filesystem;

namespace {

// A 2 x 2 x 2 hex "drum" block around (0.1, 0, 0) and a rubber bar "finger" beside it.
Mesh drum_and_finger() {
    Mesh drum = box_hex8(0.04, 0.04, 0.04, 2, 2, 2, "drum");
    drum.translate(Vec3(0.08, -0.02, -0.02));
    Mesh finger = box_hex8(0.1, 0.01, 0.01, 5, 1, 1, "finger");
    finger.translate(Vec3(0.12, -0.005, -0.005));
    Mesh m = finger;
    m.append(drum);
    return m;
}
}  // namespace

// The drum spins about its own axis at 20 rad/s until it has turned 90 degrees, then the whole
// part turns about the global z axis at 30 rad/s: every drum node sits where the composed motion
// puts it at every cycle (round-off of the central-difference update only), the part costs no
// element work (the element count is the finger's), and it is written to the VTU output.
TEST(RigidPart, FollowsAComposedMotionExactlyAndIsInTheOutput) {
    const Mesh mesh = drum_and_finger();
    ExplicitModel model(mesh);
    model.add_hex8("finger", kFingerRubber);
    const double w = 20.0, t_stop = 0.5 * std::numbers::pi / w;
    const RigidMotion spin =
        RigidMotion::rotation(Vec3(0.1, 0, 0), Vec3::UnitX(), Curve::steps({{0, w}, {t_stop, 0}}, "spin"));
    const RigidMotion turn = RigidMotion::rotation(Vec3::Zero(), Vec3::UnitZ(), Curve::steps({{0, 0}, {t_stop, 30}}));
    const RigidMotion motion = compose(turn, spin);
    model.add_rigid_part("drum", motion);
    // The finger's root face (x = 0.12, on the drum's face) rides on the drum: tied to the same motion.
    std::vector<int> root;
    for (int i = 0; i < 24; ++i)  // the finger's nodes come first
        if (std::abs(mesh.nodes[i].x() - 0.12) < 1e-12) root.push_back(i);
    ASSERT_EQ(root.size(), 4u);
    model.prescribe_motion(root, motion);
    const fs::path dir = fs::temp_directory_path() / "fem_rigid_part_test";
    fs::remove_all(dir);
    auto o = quiet(2 * t_stop);
    o.history_interval = 0.0;
    o.pvd_path = dir / "run.pvd";
    o.vtu_interval = t_stop;
    ExplicitSolver solver(model, o);
    std::vector<int> drum_nodes;
    for (int b : mesh.blocks_of_part("drum"))
        for (int n : mesh.blocks[b].connectivity) drum_nodes.push_back(n);
    double worst = 0;
    long samples = 0;
    solver.observer = [&](const ExplicitSolver& s) {
        for (int n : drum_nodes) worst = std::max(worst, (s.state().x[n] - motion.position(mesh.nodes[n], s.time())).norm());
        for (int n : root) worst = std::max(worst, (s.state().x[n] - motion.position(mesh.nodes[n], s.time())).norm());
        ++samples;
    };
    const RunSummary sum = solver.run();
    EXPECT_GT(samples, 100);
    EXPECT_LT(worst, 1e-16 * 8);  // a few ulps of the 0.1 m coordinates
    EXPECT_EQ(sum.elements, 5);
    ASSERT_EQ(sum.rigid_parts.size(), 1u);
    EXPECT_EQ(sum.rigid_parts[0], "drum");
    EXPECT_NE(sum.text().find("rigid parts: drum"), std::string::npos);
    // The drum really turned: its axis point (0.14, 0, 0) went round z by 30 (t_end - t_stop).
    const Vec3 p = motion.position(Vec3(0.14, 0, 0), solver.time());
    EXPECT_NEAR(std::atan2(p.y(), p.x()), 30 * (solver.time() - t_stop), 1e-12);
    // Energy balance with the ties' reaction work as external work.
    EXPECT_LT(sum.energy.relative_error(), 1e-2);
    // The VTU files have every element, the rigid part's too, at its moved position.
    std::ifstream f(dir / "run_0001.vtu");
    ASSERT_TRUE(f.good());
    std::stringstream ss;
    ss << f.rdbuf();
    EXPECT_NE(ss.str().find("NumberOfCells=\"13\""), std::string::npos);
    fs::remove_all(dir);
}

// A rigid part made of quadrilaterals on the finger's own root face: its nodes are the finger's
// (they carry the finger's mass), so they are tied to the motion, and the balance closes with the
// ties' reaction work as external work.
TEST(RigidPart, SharingNodesWithADeformablePartTiesThem) {
    Mesh mesh = box_hex8(0.1, 0.01, 0.01, 10, 1, 1, "finger");
    mesh.translate(Vec3(0.05, -0.005, -0.005));
    const std::vector<int> root = mesh.node_set("x0");  // 4 nodes, one face
    ElementBlock plate{"drum", ElementShape::Quad4, {}};
    plate.add(std::vector<int>{root[0], root[1], root[3], root[2]});
    mesh.blocks.push_back(plate);
    ExplicitModel model(mesh);
    model.add_hex8("finger", kFingerRubber);
    model.set_mass_damping("finger", 7.5);
    const RigidMotion drum = RigidMotion::rotation(Vec3::Zero(), Vec3::UnitZ(), Curve({{0.0, 0.0}, {0.05, 2.095}}));
    model.add_rigid_part("drum", drum);
    auto o = quiet(0.1);
    o.history_interval = 1e-3;
    ExplicitSolver solver(model, o);
    double worst = 0;
    solver.observer = [&](const ExplicitSolver& s) {
        for (int n : root) worst = std::max(worst, (s.state().x[n] - drum.position(mesh.nodes[n], s.time())).norm());
    };
    const RunSummary sum = solver.run();
    EXPECT_LT(worst, 1e-15);
    EXPECT_GT(solver.state().mass[root[0]], 0.0);
    EXPECT_GT(sum.energy.external, 0.0);
    EXPECT_LT(sum.energy.relative_error(), 1e-2);
}

TEST(RigidPart, BadDeclarationsNameThePartAndTheNode) {
    const Mesh mesh = drum_and_finger();
    {
        ExplicitModel model(mesh);
        EXPECT_THROW(model.add_rigid_part("wheel", {}), InputError);  // no such part
        model.add_rigid_part("drum", {});
        EXPECT_NE(test::input_error([&] { model.add_rigid_part("drum", {}); }).find("already rigid"), std::string::npos);
    }
    {
        ExplicitModel model(mesh);
        model.add_hex8("finger", kFingerRubber);
        model.add_hex8("drum", kFingerRubber);
        model.add_rigid_part("drum", {});
        EXPECT_NE(test::input_error([&] { ExplicitSolver s(model, quiet(1e-3)); }).find("part 'drum' is rigid"), std::string::npos);
    }
    {
        ExplicitModel model(mesh);
        model.add_hex8("finger", kFingerRubber);
        model.add_rigid_part("drum", {});
        const int shared = mesh.blocks[1].connectivity[0];
        model.prescribe_motion({shared}, RigidMotion::translation(Vec3(1, 0, 0)));
        const std::string e = test::input_error([&] { ExplicitSolver s(model, quiet(1e-3)); });
        EXPECT_NE(e.find(fmt::format("node {} follows two motions", shared)), std::string::npos) << e;
        EXPECT_NE(e.find("rigid part 'drum'"), std::string::npos) << e;
    }
}
