// Restart of explicit runs (ExplicitOptions::restart_*, ExplicitSolver::latest_restart):
//  - a killed run resumes from its latest dump and ends bit for bit where the uninterrupted run ends,
//    for a model with rotations (beams), a point mass, mass damping and an element group with history
//    variables (an elastic-perfectly-plastic tie, whose plastic offsets only its save_state /
//    restore_state carry over);
//  - a full deck restart: the restarted model adds gravity; the result is bit for bit that of one run
//    with gravity switched on at the dump's time; a restart that records other history nodes starts
//    a new history there.
// (Contact with friction and rigid parts: tests/contact/test_contact_restart.cpp.)
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

#include "core/error.hpp"
#include "explicit_test_support.hpp"
#include "io/hdf5.hpp"

using namespace fem;
namespace fs = std::filesystem;

namespace {
// Elastic-perfectly-plastic springs from nodes to the ground along y: f = k (u_y - p), |f| <= f_y,
// the plastic offset p of each node updated by the return map at every force evaluation. The forces
// depend on the history of p, which a restart must carry over.
class PlasticTieGroup final : public ElementGroup {
public:
    PlasticTieGroup(std::vector<int> nodes, double k, double fy) : nodes_(std::move(nodes)), k_(k), fy_(fy) {
        part = "plastic ties";
        p_.assign(nodes_.size(), 0.0);
    }
    std::string kind() const override { return "plastic tie"; }
    int size() const override { return static_cast<int>(nodes_.size()); }
    std::vector<int> nodes() const override { return nodes_; }
    double add_lumped_mass(NodalState&) const override { return 0.0; }
    double mass() const override { return 0.0; }
    std::vector<double> reference_time_steps() const override {
        return std::vector<double>(nodes_.size(), std::numeric_limits<double>::infinity());
    }
    void set_mass_scaling(std::vector<double>) override {}
    GroupForceResult internal_forces(NodalState& s, bool) override {
        GroupForceResult r;
        for (std::size_t i = 0; i < nodes_.size(); ++i) {
            const int n = nodes_[i];
            const double u = s.x[n].y() - s.X[n].y();
            double f = k_ * (u - p_[i]);
            if (std::abs(f) > fy_) {
                f = std::copysign(fy_, f);
                p_[i] = u - f / k_;
            }
            s.f[n].y() += f;
            r.internal_energy += 0.5 * f * f / k_;
        }
        return r;
    }
    std::vector<double> element_stress() const override { return std::vector<double>(nodes_.size(), 0.0); }
    void save_state(io::H5Writer& w, const std::string& prefix) const override { w.write(prefix + "plastic", p_); }
    void restore_state(const io::H5Reader& r, const std::string& prefix) override { p_ = r.read(prefix + "plastic"); }
    const std::vector<double>& plastic() const { return p_; }

private:
    std::vector<int> nodes_;
    double k_, fy_;
    std::vector<double> p_;
};

// A clamped steel wire (10 beams, rotations), a tip mass, a tip load pulse, mass damping, and a
// plastic tie at the tip that yields under the pulse and unloads elastically after it.
constexpr double kTie = 20.0, kYield = 0.03;  // [N/m], [N]
struct WireModel {
    Mesh mesh = line_beam2(Vec3::Zero(), Vec3(0.4, 0, 0), 10, "beam");
    std::unique_ptr<ExplicitModel> model;
    PlasticTieGroup* tie = nullptr;
    int tip = -1;
    WireModel() {
        model = std::make_unique<ExplicitModel>(mesh);
        model->add_beams("beam", ElasticMaterial::make("steel", 209e9, 0.3, 7957), {beam::Section::circular(0.6e-3)});
        tip = mesh.node_set("end")[0];
        model->add_point_mass("tip mass", tip, 0.015e-3);
        model->fix(mesh.node_set("start"), Dofs::all());
        model->add_nodal_force({tip}, Vec3(0, -0.05, 0), Curve::pulse(0.0, 0.01));
        model->set_mass_damping("beam", 2.0);
        auto tie_group = std::make_unique<PlasticTieGroup>(std::vector<int>{tip}, kTie, kYield);
        tie = tie_group.get();
        model->add_group(std::move(tie_group));
    }
};

ExplicitOptions wire_options(double end) {
    ExplicitOptions o = test::quiet(end);
    o.name = "wire";
    o.history_nodes = {{"tip", 10}};
    o.history_interval = 1e-3;
    return o;
}

bool same_bits(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

// The full deck restart tests' model: a rubber bar of 5 hexahedra (bulk viscosity, stiffness
// hourglass control) clamped at x0, a tip load pulse at x1, and with `gravity` that curve switching
// on gravity (-z, 50 g) (none: no gravity).
const Mesh kRestartBar = box_hex8(0.1, 0.02, 0.02, 5, 1, 1, "bar");
std::unique_ptr<ExplicitModel> restart_bar(std::optional<Curve> gravity) {
    auto m = std::make_unique<ExplicitModel>(kRestartBar);
    m->add_hex8("bar", ElasticMaterial::make("rubber", 6.1e6, 0.45, 1000));
    m->fix(kRestartBar.node_set("x0"));
    m->add_nodal_force(kRestartBar.node_set("x1"), Vec3(0, 0.5, 0), Curve::pulse(0.0, 1e-3));
    if (gravity) m->set_gravity(Vec3(0, 0, -9.81 * 50), *gravity);
    return m;
}
}  // namespace

TEST(ExplicitRestart, KilledRunResumesFromItsLatestDumpBitIdentically) {
    const double T = 0.04;
    const fs::path dir = fs::temp_directory_path() / "fem_explicit_restart_killed";
    fs::remove_all(dir);
    WireModel a;
    ExplicitSolver sa(*a.model, wire_options(T));
    const RunSummary ra = sa.run();
    // The "killed" run: dumps every T/4, stopped (as if killed) at 0.6 T, past the dump at T/2.
    WireModel k;
    ExplicitOptions ok = wire_options(T);
    ok.restart_interval = 0.25 * T;
    ok.restart_dir = dir;
    ExplicitSolver sk(*k.model, ok);
    sk.observer = [&](const ExplicitSolver& s) {
        if (s.time() >= 0.6 * T) s.request_stop();
    };
    sk.run();
    ASSERT_EQ(sk.restart_files().size(), 2u);  // T/4, T/2
    const fs::path latest = ExplicitSolver::latest_restart(dir, "wire");
    EXPECT_EQ(latest, sk.restart_files().back());
    EXPECT_NEAR(io::H5Reader(latest).attribute_number("/", "time"), 0.5 * T, 1e-3 * T);
    // Resume: a fresh model and solver from the latest dump, the same options.
    WireModel r;
    ExplicitOptions orr = wire_options(T);
    orr.restart_from = latest;
    ExplicitSolver sr(*r.model, orr);
    const RunSummary rr = sr.run();
    std::printf("[ restart ] wire: resumed at t = %.4g s, %ld steps in all; tip plastic offset %.4g mm (%.4g mm at the "
                "dump)\n",
                io::H5Reader(latest).attribute_number("/", "time"), rr.steps, 1e3 * r.tie->plastic()[0],
                1e3 * io::H5Reader(latest).read("groups/1/plastic")[0]);
    // The tie had yielded before the dump and is elastic at it (|k (u - p)| < f_y): its force then
    // depends on the plastic offset, which only the group's own restart state knows.
    const double p_dump = io::H5Reader(latest).read("groups/1/plastic")[0];
    const double u_dump = io::H5Reader(latest).read_matrix("state/x")(r.tip, 1);
    std::printf("[ restart ] wire: at the dump u = %.4g mm, p = %.4g mm, tie force %.4g N (yield %.3g N)\n", 1e3 * u_dump,
                1e3 * p_dump, kTie * (u_dump - p_dump), kYield);
    EXPECT_NE(p_dump, 0.0);
    EXPECT_LT(std::abs(kTie * (u_dump - p_dump)), 0.9 * kYield);
    EXPECT_EQ(rr.steps, ra.steps);
    EXPECT_TRUE(same_bits(sr.state().x, sa.state().x));
    EXPECT_TRUE(same_bits(sr.state().v, sa.state().v));
    EXPECT_TRUE(same_bits(sr.state().omega, sa.state().omega));
    ASSERT_EQ(sr.state().rotation.size(), sa.state().rotation.size());
    EXPECT_EQ(std::memcmp(sr.state().rotation.data(), sa.state().rotation.data(), sa.state().rotation.size() * sizeof(Mat3)), 0);
    EXPECT_EQ(r.tie->plastic(), a.tie->plastic());
    EXPECT_EQ(rr.energy.kinetic, ra.energy.kinetic);
    EXPECT_EQ(rr.energy.internal, ra.energy.internal);
    EXPECT_EQ(rr.energy.damping, ra.energy.damping);
    EXPECT_EQ(rr.energy.external, ra.energy.external);
    EXPECT_EQ(rr.energy.max_abs_balance_error, ra.energy.max_abs_balance_error);
    // The energy health (its scale and the largest internal and hourglass energies) carries over too.
    EXPECT_EQ(rr.energy.reference, ra.energy.reference);
    EXPECT_EQ(rr.energy.max_internal, ra.energy.max_internal);
    EXPECT_EQ(rr.energy.max_hourglass, ra.energy.max_hourglass);
    EXPECT_EQ(sr.history().time, sa.history().time);
    EXPECT_TRUE(same_bits(sr.history().nodes[0].displacement, sa.history().nodes[0].displacement));
    fs::remove_all(dir);
}

// Full deck restart: run 0..T/2 without gravity, dump, restart with a model that adds gravity. That
// is the same computation as one run with gravity switched on at T/2 (the dump is at the first step
// at or after T/2, the first one whose forces see gravity in the one run): bit for bit. A block of
// hexahedra (bulk viscosity, stiffness hourglass control) on a clamped face.
TEST(ExplicitRestart, FullDeckRestartMayChangeTheLoads) {
    const double T = 4e-3;
    const fs::path dir = fs::temp_directory_path() / "fem_explicit_restart_deck";
    fs::remove_all(dir);
    const Mesh& mesh = kRestartBar;
    auto bar = [](bool gravity, const Curve& on) { return restart_bar(gravity ? std::optional<Curve>(on) : std::nullopt); };
    auto opts = [&](double end) {
        ExplicitOptions o = test::quiet(end);
        o.name = "bar";
        o.history_nodes = {{"tip", mesh.node_set("x1")[0]}};
        o.history_interval = 2e-4;
        return o;
    };
    auto one = bar(true, Curve::step(0.5 * T));
    ExplicitSolver s1(*one, opts(T));
    const RunSummary r1 = s1.run();
    auto first = bar(false, {});
    ExplicitOptions o2 = opts(0.5 * T);
    o2.restart_times = {0.5 * T};
    o2.restart_dir = dir;
    ExplicitSolver s2(*first, o2);
    s2.run();
    ASSERT_EQ(s2.restart_files().size(), 1u);
    auto second = bar(true, {});  // gravity from the restart on
    ExplicitOptions o3 = opts(T);
    o3.restart_from = s2.restart_files()[0];
    ExplicitSolver s3(*second, o3);
    const RunSummary r3 = s3.run();
    EXPECT_EQ(r3.steps, r1.steps);
    EXPECT_TRUE(same_bits(s3.state().x, s1.state().x));
    EXPECT_TRUE(same_bits(s3.state().v, s1.state().v));
    EXPECT_EQ(r3.energy.external, r1.energy.external);
    EXPECT_EQ(r3.energy.max_abs_balance_error, r1.energy.max_abs_balance_error);
    EXPECT_EQ(s3.history().time, s1.history().time);
    EXPECT_LT(s1.state().x[mesh.node_set("x1")[0]].z() - mesh.nodes[mesh.node_set("x1")[0]].z(), 0.0);  // it sagged
    // Another set of history nodes: a new history from the restart on.
    auto third = bar(true, {});
    ExplicitOptions o4 = opts(T);
    o4.restart_from = s2.restart_files()[0];
    o4.history_nodes = {{"root", mesh.node_set("x0")[0]}};
    ExplicitSolver s4(*third, o4);
    s4.run();
    EXPECT_EQ(s4.history().time.front(), s2.time());
    EXPECT_TRUE(same_bits(s4.state().x, s1.state().x));
    // Options that ask for dumps need a directory.
    ExplicitOptions bad = opts(T);
    bad.restart_interval = 1e-3;
    EXPECT_THROW(ExplicitSolver(*bar(false, {}), bad), InputError);
    fs::remove_all(dir);
}

// A branch of a shared start (ExplicitOptions::vtu_series_from_restart): the bar runs without gravity
// to T/2 and dumps (the shared start, its own folder); a branch restarts from that dump with gravity
// into another folder. The branch ends bit for bit where one uninterrupted run with gravity from T/2
// ends, and its PVD lists the start's VTU files written before the dump (relative paths into the
// start's folder), then its own, numbered on from them, each the uninterrupted run's file byte for
// byte. Without the option the branch's series starts at the restart.
TEST(ExplicitRestart, BranchOfASharedStartContinuesItsVtuSeries) {
    const double T = 4e-3;
    const fs::path dir = fs::temp_directory_path() / "fem_explicit_restart_branch";
    fs::remove_all(dir);
    auto bar = [](const Curve& gravity_on) { return restart_bar(gravity_on); };
    auto opts = [&](double end, const fs::path& pvd) {
        ExplicitOptions o = test::quiet(end);
        o.name = "bar";
        o.pvd_path = pvd;
        o.vtu_interval = 0.5e-3;
        return o;
    };
    auto read_file = [](const fs::path& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    // One run, gravity switched on at T/2 (the curve's step: zero before, one after).
    auto whole = bar(Curve::step(0.5 * T));
    ExplicitSolver s1(*whole, opts(T, dir / "whole" / "bar.pvd"));
    s1.run();
    // The shared start: no gravity, dumped at T/2.
    auto first = bar(Curve::constant(0.0));
    ExplicitOptions o2 = opts(0.5 * T, dir / "start" / "start.pvd");
    o2.restart_times = {0.5 * T};
    o2.restart_dir = dir / "start";
    ExplicitSolver s2(*first, o2);
    s2.run();
    ASSERT_EQ(s2.restart_files().size(), 1u);
    const fs::path dump = s2.restart_files()[0];
    EXPECT_EQ(ExplicitSolver::restart_time(dump), s2.time());
    EXPECT_THROW(ExplicitSolver::restart_time(dir / "start" / "start_0000.vtu"), std::exception);
    // The branch: gravity on from the restart.
    auto second = bar(Curve::constant(1.0));
    ExplicitOptions o3 = opts(T, dir / "branch" / "branch.pvd");
    o3.restart_from = dump;
    o3.vtu_series_from_restart = true;
    fs::create_directories(dir / "branch");
    ExplicitSolver s3(*second, o3);
    s3.run();
    EXPECT_TRUE(same_bits(s3.state().x, s1.state().x));
    EXPECT_TRUE(same_bits(s3.state().v, s1.state().v));
    // The series: the start's files before the dump, then the branch's own.
    const std::string pvd = read_file(dir / "branch" / "branch.pvd");
    const std::string whole_pvd = read_file(dir / "whole" / "bar.pvd");
    int listed = 0, from_start = 0;
    for (std::size_t at = pvd.find("file=\""); at != std::string::npos; at = pvd.find("file=\"", at + 1)) {
        const std::string file = pvd.substr(at + 6, pvd.find('"', at + 6) - at - 6);
        const std::string index = file.substr(file.size() - 8, 4);  // NNNN of <stem>_NNNN.vtu
        if (file.rfind("../start/start_", 0) == 0) ++from_start;
        else EXPECT_EQ(file, "branch_" + index + ".vtu");
        ASSERT_TRUE(fs::exists(dir / "branch" / file)) << file;
        EXPECT_EQ(read_file(dir / "branch" / file), read_file(dir / "whole" / ("bar_" + index + ".vtu"))) << file;
        ++listed;
    }
    // 0, 0.5, 1.0, 1.5 ms (and 2 ms when its cycle wrote the VTU before the dump): the start's files
    EXPECT_GE(from_start, 4);
    EXPECT_LE(from_start, 5);
    int whole_listed = 0;
    for (std::size_t at = whole_pvd.find("file=\""); at != std::string::npos; at = whole_pvd.find("file=\"", at + 1)) ++whole_listed;
    EXPECT_EQ(listed, whole_listed);
    // Without the option: the series starts at the restart.
    auto third = bar(Curve::constant(1.0));
    ExplicitOptions o4 = opts(T, dir / "alone" / "alone.pvd");
    o4.restart_from = dump;
    fs::create_directories(dir / "alone");
    ExplicitSolver s4(*third, o4);
    s4.run();
    const std::string alone = read_file(dir / "alone" / "alone.pvd");
    EXPECT_TRUE(fs::exists(dir / "alone" / "alone_0000.vtu"));
    EXPECT_EQ(alone.find("start_"), std::string::npos) << alone;
    fs::remove_all(dir);
}
