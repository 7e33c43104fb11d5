// The explicit case file (lib/explicit_case): one small case per feature against its closed form,
// restart through the case file, and the football_sweep case file against the study's C++ model.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <tuple>

#include <fmt/format.h>

#include <csignal>

#include <unistd.h>

#include "core/progress.hpp"
#include "explicit/parallel.hpp"

#include "core/error.hpp"
#include "explicit_case/case_file.hpp"
#include "hand/football.hpp"

namespace fs = std::filesystem;
using namespace fem;
using namespace fem::explicit_case;

namespace {

const fs::path kSource = FEM_SOURCE_DIR;
const fs::path kCases = kSource / "tests/explicit_case/cases";

fs::path scratch(const std::string& name) {
    const fs::path p = fs::temp_directory_path() / ("fem_explicit_case_" + std::to_string(::getpid())) / name;
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

// Runs a case in-process (no output files unless asked) and returns the solver for its history.
struct CaseRun {
    ExplicitCase c;
    std::unique_ptr<CaseModel> model;
    std::unique_ptr<ExplicitSolver> solver;
    RunSummary summary;
    CaseRun(ExplicitCase c_, const fs::path& folder, bool files = false) : c(std::move(c_)) {
        model = std::make_unique<CaseModel>(c);
        ExplicitOptions o = solver_options(c, *model, folder);
        if (!files) o.h5_path.clear(), o.pvd_path.clear();
        o.progress = false;
        solver = std::make_unique<ExplicitSolver>(model->model(), o);
        summary = solver->run();
    }
    // Node history `name`: displacement component d at the sample nearest to t.
    double u(const std::string& name, int d, double t) const {
        const History& h = solver->history();
        std::size_t best = 0;
        for (std::size_t i = 0; i < h.time.size(); ++i)
            if (std::abs(h.time[i] - t) < std::abs(h.time[best] - t)) best = i;
        for (const auto& n : h.nodes)
            if (n.name == name) return n.displacement[best][d];
        ADD_FAILURE() << "no history node " << name;
        return NAN;
    }
    double time_near(double t) const {
        const History& h = solver->history();
        double best = h.time.front();
        for (double s : h.time)
            if (std::abs(s - t) < std::abs(best - t)) best = s;
        return best;
    }
};

// A bar struck at one end with v0, free at the other: the free end stays at rest until the wave
// arrives at L/c, then moves at 2 v0 (reflection at a free end): u = 2 v0 (t - L/c).
TEST(ExplicitCase, BarWaveMatchesTheClosedForm) {
    CaseRun r(read_case(kCases / "bar_wave.toml"), scratch("bar"));
    const double c = std::sqrt(210e9 / 7800.0), L = 1.0, v0 = 1.0;
    EXPECT_LT(std::abs(r.u("free_end", 0, 0.9 * L / c)), 1e-3 * v0 * L / c);  // not arrived yet
    for (double f : {1.5, 2.0}) {
        const double t = r.time_near(f * L / c), exact = 2.0 * v0 * (t - L / c);
        EXPECT_NEAR(r.u("free_end", 0, t), exact, 0.005 * exact) << "t = " << f << " L/c";
    }
}

// A rigid plate moving at V under a block at rest (gravity, Coulomb friction mu): the block
// accelerates at mu g until it sticks at t* = V / (mu g).
TEST(ExplicitCase, RigidPlateDragsABlockWithFriction) {
    CaseRun r(read_case(kCases / "plate_drags_block.toml"), scratch("plate"));
    const double mu = 0.3, g = 9.81, V = 0.3, ts = V / (mu * g);
    auto exact = [&](double t) { return t < ts ? 0.5 * mu * g * t * t : 0.5 * mu * g * ts * ts + V * (t - ts); };
    for (double t0 : {0.05, 0.08, 0.12, 0.15}) {
        const double t = r.time_near(t0);
        EXPECT_NEAR(r.u("top", 0, t), exact(t), 0.01 * exact(t)) << "t = " << t;
    }
    EXPECT_NEAR(r.u("top", 1, 0.15), 0.0, 1e-4);  // stays on the plate (penetration of the penalty)
}

// A run restarted from a dump of the case's own restart_times continues bit for bit (friction
// history included) as the uninterrupted run.
TEST(ExplicitCase, RestartFromTheCaseFileContinuesBitIdentically) {
    ExplicitCase c = read_case(kCases / "plate_drags_block.toml");
    c.control.end_time = 0.04;
    c.control.restart_times = {0.02};
    const fs::path dir = scratch("restart");
    CaseRun whole(c, dir, true);
    ASSERT_EQ(whole.solver->restart_files().size(), 1u);
    ExplicitCase rc = c;
    rc.control.restart_times.clear();
    rc.control.restart_from = whole.solver->restart_files().front();
    CaseRun resumed(rc, scratch("restart2"));
    const NodalState& a = whole.solver->state();
    const NodalState& b = resumed.solver->state();
    EXPECT_EQ(whole.solver->step(), resumed.solver->step());
    ASSERT_EQ(a.x.size(), b.x.size());
    for (std::size_t i = 0; i < a.x.size(); ++i) {
        EXPECT_EQ(a.x[i], b.x[i]) << "node " << i;
        EXPECT_EQ(a.v[i], b.v[i]) << "node " << i;
    }
}

// fem-explicit end to end: the run's files in its folder, as one set.
TEST(ExplicitCase, RunWritesItsFilesAsOneSet) {
    ExplicitCase c = read_case(kCases / "bar_wave.toml");
    c.output.folder = scratch("files") / "out";
    c.output.vtu_interval = 1e-4;
    const std::string text = run_case(c, true);
    EXPECT_NE(text.find("element-cycles/s"), std::string::npos);
    EXPECT_NE(text.find("energy balance"), std::string::npos);
    EXPECT_NE(text.find("health: pass"), std::string::npos) << text;
    for (const char* f : {"summary.txt", "run.json", "histories.h5", "histories.dat", "energies.dat", "von_mises.dat", "results.pvd",
                          "manifest.txt"})
        EXPECT_TRUE(fs::exists(c.output.folder / f)) << f;
}

// Ctrl-C (SIGINT under the solver's InterruptGuard): the run stops, writes the state reached marked
// partial, commits the set and reports Interrupted (fem-explicit exits 130).
TEST(ExplicitCase, InterruptedRunWritesAPartialSet) {
    ExplicitCase c = read_case(kCases / "bar_wave.toml");
    c.output.folder = scratch("interrupted") / "out";
    bool interrupted = false;
    {
        const InterruptGuard guard;  // SIGINT now only sets the flag the solver polls every cycle
        std::raise(SIGINT);
        try {
            run_case(c, true);
        } catch (const Interrupted& e) {
            interrupted = true;
            EXPECT_NE(std::string(e.what()).find("partial"), std::string::npos) << e.what();
        }
        clear_interrupt();
    }
    EXPECT_TRUE(interrupted);
    EXPECT_TRUE(fs::exists(c.output.folder / "PARTIAL.txt"));
    EXPECT_TRUE(fs::exists(c.output.folder / "histories.dat"));
    EXPECT_TRUE(fs::exists(c.output.folder / "manifest.txt"));
}

// studies/football_sweep/football_sweep.toml is the study's Case 4 scene (lib/hand/football.hpp):
// the same mesh, masses, parts, rigid parts and contact pairs, and the same first steps bit for bit.
TEST(ExplicitCase, FootballCaseFileBuildsTheStudysModel) {
    const ExplicitCase c = read_case(kSource / "studies/football_sweep/football_sweep.toml");
    CaseModel ours(c);
    ASSERT_NE(ours.hand_model(), nullptr);
    const hand::football::Case case4 = hand::football::table_4_4()[3];
    ASSERT_EQ(case4.id, 4);
    hand::HandModel ref(hand::football::scene(case4));

    const Mesh& a = ours.mesh();
    const Mesh& b = ref.mesh();
    ASSERT_EQ(a.node_count(), b.node_count());
    for (int i = 0; i < a.node_count(); ++i) ASSERT_EQ(a.nodes[i], b.nodes[i]) << "node " << i;
    ASSERT_EQ(a.blocks.size(), b.blocks.size());
    for (std::size_t k = 0; k < a.blocks.size(); ++k) {
        EXPECT_EQ(a.blocks[k].part, b.blocks[k].part);
        EXPECT_EQ(a.blocks[k].shape, b.blocks[k].shape);
        EXPECT_EQ(a.blocks[k].connectivity, b.blocks[k].connectivity);
    }
    EXPECT_EQ(a.node_sets, b.node_sets);
    for (const std::string part : {"finger-A", "finger-B", "finger-C", "finger-D", "finger-E", "football"})
        EXPECT_EQ(ours.hand_model()->part_mass(part), ref.part_mass(part)) << part;
    std::vector<std::string> ref_pairs;
    for (const auto& p : ref.pairs()) ref_pairs.push_back(p.name);
    EXPECT_EQ(ours.contact_pairs(), ref_pairs);
    std::vector<std::string> rigid_a, rigid_b;
    for (const auto& m : ours.model().motions()) rigid_a.push_back(m.part);
    for (const auto& m : ref.model().motions()) rigid_b.push_back(m.part);
    EXPECT_EQ(rigid_a, rigid_b);

    // The first steps, with the same solver options (one thread: at a load of 2 per core a
    // two-thread run of these 20 cycles took 15 x longer than one thread).
    par::set_threads(1);
    ExplicitOptions o = solver_options(c, ours, scratch("football"));
    o.h5_path.clear(), o.pvd_path.clear();
    o.progress = false;
    o.end_time = 1e-4;  // about 20 cycles
    o.hex_stability_check = false;  // the same solver code on both models; the Lanczos measurement costs seconds
    o.history_interval = 0.0;
    ExplicitSolver sa(ours.model(), o), sb(ref.model(), o);
    sa.run();
    sb.run();
    EXPECT_GE(sa.step(), 15);
    EXPECT_EQ(sa.step(), sb.step());
    for (std::size_t i = 0; i < sa.state().x.size(); ++i) {
        ASSERT_EQ(sa.state().x[i], sb.state().x[i]) << "node " << i;
        ASSERT_EQ(sa.state().v[i], sb.state().v[i]) << "node " << i;
    }
}

// Rigid motions compose in file order (the first innermost): a rotation about z at omega, then a
// translation at v along x (the order matters): x(t) = Rz(omega t) X + v t. Nodes that `follow` the rigid part move with it exactly.
TEST(ExplicitCase, ComposedRigidMotionMovesFollowingNodes) {
    const std::string text = R"(
[control]
end_time = 1.0e-3
[[material]]
name = "soft"
E = 1.0e6
nu = 0.3
rho = 1000.0
[[part]]
name = "block"
material = "soft"
mesh = "box"
size = [0.1, 0.1, 0.1]
origin = [0.2, 0.0, 0.0]
elements = [1, 1, 1]
[[rigid_part]]
name = "carrier"
mesh = "plate"
centre = [0.0, 0.0, 0.0]
u = [0.1, 0.0, 0.0]
v = [0.0, 0.1, 0.0]
segments = [1, 1]
[[rigid_part.motion]]
type = "rotation"
axis = [0.0, 0.0, 1.0]
omega = 100.0
[[rigid_part.motion]]
type = "translation"
direction = [1.0, 0.0, 0.0]
speed = 2.0
[[boundary]]
set = "x0-block"
follow = "carrier"
)";
    CaseRun r(parse_case(text, "composed.toml"), scratch("composed"));
    const double t = r.solver->time(), theta = 100.0 * t;
    EXPECT_GT(theta, 0.05);
    const Mesh& mesh = r.model->mesh();
    for (int n : mesh.node_set("x0-block")) {
        const Vec3 X = mesh.nodes[n];
        const Vec3 exact(std::cos(theta) * X.x() - std::sin(theta) * X.y() + 2.0 * t,
                         std::sin(theta) * X.x() + std::cos(theta) * X.y(), X.z());
        EXPECT_LT((r.solver->state().x[n] - exact).norm(), 1e-12) << "node " << n;
    }
}

// Parts from files: a CalculiX deck (its *NSET ROOT) and a Gmsh mesh (physical group "root"), each
// clamped there and sagging under gravity.
TEST(ExplicitCase, PartsFromADeckAndAGmshFile) {
    for (const auto& [kind, file, set, elements] :
         {std::tuple{"deck", "deck.inp", "ROOT-beam", 4}, std::tuple{"gmsh", "block.msh", "root-beam", 1}}) {
        const std::string text = fmt::format(R"(
[control]
end_time = 2.0e-4
[[material]]
name = "steel"
E = 210e9
nu = 0.3
rho = 7800.0
[[part]]
name = "beam"
material = "steel"
mesh = "{}"
file = "{}"
[[boundary]]
set = "{}"
fix = ["all"]
[gravity]
g = [0.0, -9.81, 0.0]
)",
                                             kind, file, set);
        CaseRun r(parse_case(text, std::string(kind) + ".toml", kSource / "tests/bad_input/inputs/modal"), scratch(kind));
        const Mesh& mesh = r.model->mesh();
        EXPECT_EQ(mesh.element_count(), elements) << kind;
        const auto& root = mesh.node_set(set);
        double sag = 0.0;
        for (int n = 0; n < mesh.node_count(); ++n) {
            const double uy = r.solver->state().x[n].y() - mesh.nodes[n].y();
            if (std::find(root.begin(), root.end(), n) != root.end()) EXPECT_EQ(uy, 0.0) << kind << " root node " << n;
            else sag = std::min(sag, uy);
        }
        EXPECT_LT(sag, 0.0) << kind;
    }
}

// An ellipsoid part given its mass: the density is the mass over the mesh volume.
TEST(ExplicitCase, EllipsoidPartWithAGivenMass) {
    const std::string text = R"(
[control]
end_time = 1.0e-6
threads = 1
[[material]]
name = "rubber"
E = 6.1e6
nu = 0.49
rho = 1000.0
[[part]]
name = "ball"
material = "rubber"
mesh = "ellipsoid"
semi_axes = [0.05, 0.03, 0.03]
grid = [4, 4, 2, 2]
mass = 0.125
)";
    CaseRun r(parse_case(text, "ball.toml"), scratch("ball"));
    EXPECT_NEAR(r.summary.mass, 0.125, 1e-12);
}

TEST(ExplicitCase, ReaderRefusesWithFileLineAndKey) {
    auto refused = [](const std::string& text) {
        try {
            parse_case(text, "bad.toml");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    const std::string base = "[control]\nend_time = 1.0\n[[material]]\nname = \"m\"\nE = 1e6\nnu = 0.3\nrho = 1000.0\n"
                             "[[part]]\nname = \"b\"\nmaterial = \"m\"\nmesh = \"box\"\nsize = [1.0, 1.0, 1.0]\nelements = [1, 1, 1]\n";
    EXPECT_EQ(refused(base), "accepted");
    EXPECT_NE(refused(base + "elemnts = [1, 1, 1]\n").find("bad.toml:14: part[0].elemnts: is not a key of a 'box' part (did you mean 'elements'?)"), std::string::npos)
        << refused(base + "elemnts = [1, 1, 1]\n");
    EXPECT_NE(refused(base + "[[contact]]\nslave = \"b\"\nmaster = \"flor\"\n").find("master: 'flor' is not a part or rigid part"), std::string::npos);
    EXPECT_NE(refused(base + "[gravity]\ng = [0.0, nan, 0.0]\n").find("g[1]: must be a finite number"), std::string::npos);
    EXPECT_NE(refused(base + "[[boundary]]\nset = \"x0-b\"\nfix = [\"x\"]\nvelocity = [1.0, 0.0, 0.0]\n").find("give exactly one of fix"), std::string::npos);
}

}  // namespace
