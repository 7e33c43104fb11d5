// Outputs of the explicit solver: HDF5 time histories, the VTU/PVD series, the run summary (text and
// JSON for Study::record_run), loads by curves, gravity switched on at a time, prescribed displacement.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include <fmt/format.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "explicit/solver.hpp"
#include "io/hdf5.hpp"
#include "explicit_test_support.hpp"

using namespace fem;
using namespace fem::test;
namespace fs = std::filesystem;

namespace {

// A steel bar clamped at x = 0 and pulled sideways at its free end (10 N per node, ramped over 0.1 ms).
std::unique_ptr<ExplicitModel> pulled_bar(const Mesh& mesh) {
    auto model = std::make_unique<ExplicitModel>(mesh);
    model->add_hex8("bar", kSteel);
    model->fix(mesh.node_set("x0"), Dofs::all());
    model->add_nodal_force(mesh.node_set("x1"), Vec3(0, 10, 0), Curve({{0, 0}, {1e-4, 1}}));
    return model;
}
}

TEST(ExplicitOutput, WritesHistoriesVtuAndSummary) {
    const fs::path dir = fs::temp_directory_path() / "fem_explicit_output_test";
    fs::remove_all(dir);
    fs::create_directories(dir);
    Mesh mesh = box_hex8(0.1, 0.02, 0.02, 5, 1, 1, "bar");
    auto model = pulled_bar(mesh);
    const int tip = mesh.node_set("x1")[0];
    ExplicitOptions o;
    o.end_time = 2e-4;
    o.progress = false;
    o.print_summary = false;
    o.name = "output test";
    o.history_nodes = {{"tip", tip}};
    o.history_interval = 1e-5;
    o.h5_path = dir / "run.h5";
    o.pvd_path = dir / "run.pvd";
    o.vtu_interval = 5e-5;
    ExplicitSolver solver(*model, o);
    const RunSummary sum = solver.run();
    ASSERT_TRUE(fs::exists(o.h5_path));
    ASSERT_TRUE(fs::exists(o.pvd_path));
    const auto t = io::read_h5_matrix(o.h5_path, "time");
    const auto u = io::read_h5_matrix(o.h5_path, "history/tip/displacement");
    ASSERT_EQ(t.size(), static_cast<long>(solver.history().time.size()));
    ASSERT_EQ(u.rows(), t.size());
    EXPECT_EQ(u.cols(), 3);
    EXPECT_DOUBLE_EQ(u(u.rows() - 1, 1), solver.history().nodes[0].displacement.back().y());
    EXPECT_GT(u(u.rows() - 1, 1), 0.0);  // pushed in +y
    const auto vm = io::read_h5_matrix(o.h5_path, "max_von_mises/bar");
    EXPECT_GT(vm(vm.size() - 1), 0.0);
    // 0, 5e-5, 1e-4, 1.5e-4, 2e-4 (+ the last state): at least 5 VTU files.
    int vtu = 0;
    for (const auto& e : fs::directory_iterator(dir)) vtu += e.path().extension() == ".vtu";
    EXPECT_GE(vtu, 5);
    // Summary: text and JSON carry the controlling element and the energies.
    EXPECT_NE(sum.text().find("controlling element: part 'bar' block 0 hex8 element"), std::string::npos);
    const nlohmann::json j = sum.to_json();
    EXPECT_EQ(j["nodes"], mesh.node_count());
    EXPECT_EQ(j["elements"], 5);
    EXPECT_GT(j["steps"].get<long>(), 10);
    EXPECT_GT(j["external_work_J"].get<double>(), 0.0);
    EXPECT_LT(sum.energy.relative_error(), 1e-2);
    fs::remove_all(dir);
}

// Gravity switched on at t_on: before it nothing moves; after it a free body falls with the
// constant acceleration g. Central differences integrate a constant acceleration exactly: the
// second difference of the displacement over the step is g (1e-9 relative). The force acts from the
// first step time t_k >= t_on, and the scheme's force at t_k stands for [t_k - dt/2, t_k + dt/2], so
// the final velocity is g (t_end + dt/2 - t_k) (a first version of this test compared with the
// continuous u = g (t - t_on)^2 / 2 and ignored this half-step timing).
TEST(ExplicitLoads, GravitySwitchedOnAtATime) {
    Mesh mesh = line_beam2(Vec3::Zero(), Vec3(0.1, 0, 0), 2, "wire");
    ExplicitModel model(mesh);
    model.add_beams("wire", kSteel, {beam::Section::circular(1e-3)});
    const double t_on = 1e-3, g = 9.81;
    model.set_gravity(Vec3(0, 0, -g), t_on);
    ExplicitOptions o;
    o.end_time = 3e-3;
    o.progress = false;
    o.print_summary = false;
    o.history_nodes = {{"a", 0}};
    ExplicitSolver solver(model, o);
    const auto sum = solver.run();
    const auto& h = solver.history();
    double t_k = -1;
    for (std::size_t i = 0; i < h.time.size(); ++i) {
        if (h.time[i] <= t_on) {
            EXPECT_EQ(h.nodes[0].displacement[i].z(), 0.0) << h.time[i];
        }
        if (t_k < 0 && h.time[i] >= t_on) t_k = h.time[i];
    }
    const std::size_t n = h.time.size();
    // constant step (a rigid fall does not change it): second difference = -g dt^2
    const double dt = h.time[n - 2] - h.time[n - 3];
    const double d2 = h.nodes[0].displacement[n - 2].z() - 2 * h.nodes[0].displacement[n - 3].z() +
                      h.nodes[0].displacement[n - 4].z();
    EXPECT_NEAR(d2 / (dt * dt), -g, 1e-6 * g);
    // Work of gravity = kinetic energy (rigid fall): the balance closes to round-off.
    EXPECT_LT(sum.energy.relative_error(), 1e-9);
    EXPECT_NEAR(solver.state().v[0].z(), -g * (solver.time() - dt / 2 - t_k + dt / 2), 1e-9 * g * 2e-3);
}

// Prescribed displacement by a curve: the node follows it exactly at every step.
TEST(ExplicitLoads, PrescribedDisplacementIsFollowedExactly) {
    Mesh mesh = box_hex8(0.1, 0.02, 0.02, 5, 1, 1, "bar");
    ExplicitModel model(mesh);
    model.add_hex8("bar", kSteel);
    model.fix(mesh.node_set("x0"), Dofs::all());
    const Curve c({{0, 0}, {1e-4, 1}, {2e-4, 1}});
    model.prescribe_displacement(mesh.node_set("x1"), 0, 1e-5, c);
    ExplicitOptions o;
    o.end_time = 2e-4;
    o.progress = false;
    o.print_summary = false;
    const int n = mesh.node_set("x1")[0];
    o.history_nodes = {{"end", n}};
    ExplicitSolver solver(model, o);
    const auto sum = solver.run();
    const auto& h = solver.history();
    for (std::size_t i = 0; i < h.time.size(); ++i)
        EXPECT_NEAR(h.nodes[0].displacement[i].x(), 1e-5 * c(h.time[i]), 1e-12) << h.time[i];
    // The reaction's work is the external work: balance closes to the bulk-viscosity bookkeeping.
    EXPECT_GT(sum.energy.external, 0.0);
    EXPECT_LT(sum.energy.relative_error(), 1e-2);
}

TEST(ExplicitInput, BadRequestsNameTheCulprit) {
    Mesh mesh = box_hex8(0.1, 0.02, 0.02, 2, 1, 1, "bar");
    ExplicitModel model(mesh);
    EXPECT_THROW(model.add_hex8("finger", kSteel), InputError);  // no such part
    model.add_hex8("bar", kSteel);
    model.set_mass_damping("nothere", 1.0);
    ExplicitOptions o;
    o.end_time = 1e-4;
    try {
        ExplicitSolver s(model, o);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("nothere"), std::string::npos);
    }
    EXPECT_THROW(Curve({{0, 1}, {0, 2}, {0, 3}}, "bad"), InputError);
    EXPECT_THROW(model.prescribe_velocity({0}, 4, 1.0), InputError);
}

namespace {
// A penalty wall z >= 0 as a ForceProvider: f = -k z on nodes below it (a stand-in for contact).
class PenaltyWall final : public ForceProvider {
public:
    explicit PenaltyWall(double k) : k_(k) {}
    std::string name() const override { return "wall"; }
    void add_forces(double, const NodalState& s, std::vector<Vec3>& f, std::vector<Vec3>&) override {
        for (int i = 0; i < s.node_count(); ++i)
            if (s.x[i].z() < 0) f[i].z() -= k_ * s.x[i].z();
    }
    double stable_time_step(const NodalState& s) const override {
        double m = 1e300;
        for (double mi : s.mass) m = std::min(m, mi);
        return 2.0 * std::sqrt(m / k_);
    }

private:
    double k_;
};
}  // namespace

// A force provider (the hook contact uses): a block dropped on a penalty wall bounces back; the
// work of the wall is reported as contact energy and the balance closes (1e-3: the penalty
// spring is linear, the block elastic and undamped; the residual is the O(dt^2) contact onset).
TEST(ExplicitForceProvider, PenaltyWallBounceClosesTheEnergyBalance) {
    Mesh mesh = box_hex8(0.02, 0.02, 0.02, 2, 2, 2, "block");
    mesh.translate(Vec3(0, 0, 1e-4));
    ExplicitModel model(mesh);
    model.add_hex8("block", kSteel);
    model.set_initial_velocity([](const Vec3&) { return Vec3(0, 0, -1.0); });
    model.add_force_provider(std::make_unique<PenaltyWall>(1e8));
    ExplicitOptions o;
    o.end_time = 1e-3;
    o.progress = false;
    o.print_summary = false;
    ExplicitSolver solver(model, o);
    double max_contact = 0;
    solver.observer = [&](const ExplicitSolver& s) { max_contact = std::max(max_contact, s.history().contact.back()); };
    const auto sum = solver.run();
    double vz = 0, m = 0;
    for (int i = 0; i < mesh.node_count(); ++i) {
        vz += solver.state().mass[i] * solver.state().v[i].z();
        m += solver.state().mass[i];
    }
    std::printf("penalty wall: rebound velocity %.4f m/s, max contact energy %.3g J of %.3g J, energy error %.2e\n",
                vz / m, max_contact, sum.energy.initial, sum.energy.relative_error());
    EXPECT_GT(vz / m, 0.5);                          // it bounced
    EXPECT_GT(max_contact, 0.1 * sum.energy.initial);  // the wall stored energy on the way
    EXPECT_LT(sum.energy.relative_error(), 1e-3);
}

// Nodes tied to a rigid rotation follow it exactly (the finger root on the drum).
TEST(ExplicitLoads, PrescribedMotionIsFollowedExactly) {
    Mesh mesh = box_hex8(0.1, 0.01, 0.01, 10, 1, 1, "finger");
    mesh.translate(Vec3(0.05, -0.005, -0.005));
    ExplicitModel model(mesh);
    model.add_hex8("finger", ElasticMaterial::make("rubber", 6.1e6, 0.45, 1000));
    const auto angle = [](double t) { return 10.0 * t * t; };
    const auto pos = [&](const Vec3& X, double t) {
        return Vec3(Eigen::AngleAxisd(angle(t), Vec3::UnitZ()).toRotationMatrix() * X);
    };
    const auto& root = mesh.node_set("x0");
    model.prescribe_motion(root, pos);
    model.set_mass_damping("finger", 7.5);
    ExplicitOptions o;
    o.end_time = 0.05;
    o.progress = false;
    o.print_summary = false;
    o.history_interval = 1e-3;
    ExplicitSolver solver(model, o);
    double worst = 0;
    solver.observer = [&](const ExplicitSolver& s) {
        for (int n : root) worst = std::max(worst, (s.state().x[n] - pos(mesh.nodes[n], s.time())).norm());
    };
    solver.run();
    EXPECT_LT(worst, 1e-12);
}

// An observer can end the run early (e.g. once contact is over); the summary reports the time reached.
TEST(ExplicitOutput, ObserverCanStopTheRun) {
    Mesh mesh = box_hex8(0.1, 0.02, 0.02, 5, 1, 1, "bar");
    auto model = pulled_bar(mesh);
    ExplicitOptions o;
    o.end_time = 1e-3;
    o.progress = false;
    o.print_summary = false;
    o.history_interval = 1e-5;
    ExplicitSolver solver(*model, o);
    solver.observer = [](const ExplicitSolver& s) {
        if (s.time() >= 2e-4) s.request_stop();
    };
    const RunSummary sum = solver.run();
    EXPECT_GE(sum.end_time, 2e-4);
    EXPECT_LT(sum.end_time, 2e-4 + 2e-5);  // stopped at the first sample at or after 0.2 ms
    EXPECT_NEAR(solver.history().time.back(), sum.end_time, 1e-15);
}

// The observer on its own schedule: every cycle (observer_interval 0) while the history stores a
// sample every 0.1 ms only, or every 50 us; max_von_mises(part) is this cycle's element maximum, the
// same as the history's maxima when the history stores every cycle.
TEST(ExplicitOutput, ObserverIntervalIsIndependentOfTheHistory) {
    Mesh mesh = box_hex8(0.1, 0.02, 0.02, 5, 1, 1, "bar");
    std::vector<double> vm_every_cycle, vm_history;
    long calls = 0;
    {
        auto model = pulled_bar(mesh);
        ExplicitOptions o;
        o.end_time = 1e-3, o.progress = false, o.print_summary = false, o.history_interval = 1e-4, o.observer_interval = 0;
        ExplicitSolver solver(*model, o);
        solver.observer = [&](const ExplicitSolver& s) {
            ++calls;
            vm_every_cycle.push_back(s.max_von_mises("bar"));
        };
        const RunSummary sum = solver.run();
        EXPECT_EQ(calls, sum.steps + 1);  // the start and every cycle
        EXPECT_LE(solver.history().time.size(), 12u);
        EXPECT_EQ(solver.max_von_mises("nothere"), 0.0);
    }
    {
        auto model = pulled_bar(mesh);
        ExplicitOptions o;
        o.end_time = 1e-3, o.progress = false, o.print_summary = false, o.history_interval = 0.0;
        ExplicitSolver solver(*model, o);
        solver.run();
        vm_history = solver.history().max_von_mises.at("bar");
    }
    EXPECT_EQ(vm_every_cycle, vm_history);
    {
        auto model = pulled_bar(mesh);
        ExplicitOptions o;
        o.end_time = 1e-3, o.progress = false, o.print_summary = false, o.history_interval = 0.0, o.observer_interval = 5e-5;
        ExplicitSolver solver(*model, o);
        std::vector<double> t;
        solver.observer = [&](const ExplicitSolver& s) { t.push_back(s.time()); };
        const RunSummary sum = solver.run();
        ASSERT_GE(t.size(), 20u);
        EXPECT_LE(t.size(), 22u);  // 0, ~every 50 us to 1 ms, and the end
        for (std::size_t i = 1; i + 1 < t.size(); ++i) EXPECT_GE(t[i] - t[i - 1], 5e-5 * (1 - 1e-9));
        EXPECT_EQ(t.back(), sum.end_time);
    }
}

// The summary splits the wall time like LS-DYNA's timing table: every phase >= 0, the phases and
// "other" add up to the wall time, element forces took time, text and JSON carry the table.
TEST(ExplicitOutput, SummarySplitsTheWallTime) {
    Mesh mesh = box_hex8(0.1, 0.02, 0.02, 20, 4, 4, "bar");
    auto model = pulled_bar(mesh);
    ExplicitOptions o;
    o.end_time = 2e-4;
    o.progress = false;
    o.print_summary = false;
    ExplicitSolver solver(*model, o);
    const RunSummary sum = solver.run();
    const TimingSummary& T = sum.timing;
    for (double t : {T.elements, T.contact_search, T.contact_forces, T.constraints, T.update, T.output, T.other})
        EXPECT_GE(t, 0.0);
    EXPECT_GT(T.elements, 0.0);
    EXPECT_GT(T.update, 0.0);
    EXPECT_EQ(T.contact_search + T.contact_forces, 0.0);  // no contact
    const double total = T.elements + T.contact_search + T.contact_forces + T.constraints + T.update + T.output + T.other;
    EXPECT_NEAR(total, sum.wall_s, 1e-9 + 1e-9 * sum.wall_s);
    EXPECT_GE(T.clock_reads, 5 * sum.steps);  // five laps per cycle without contact
    EXPECT_GT(T.timer_overhead, 0.0);
    EXPECT_NE(sum.text().find("element forces"), std::string::npos);
    const nlohmann::json j = sum.to_json();
    EXPECT_EQ(j["timing_s"]["elements"].get<double>(), T.elements);
    EXPECT_EQ(j["contact_share"].get<double>(), 0.0);
    EXPECT_TRUE(j["contact_interfaces"].empty());
}

// The energy health over a judged window (ExplicitOptions::health_until/health_from, EnergySummary):
// a run to 4e-4 s judged to 2e-4 s has exactly the health of a run that ends at 2e-4 s, whatever
// follows; through a restart dump inside the window the window carries on bit for bit; a window that
// starts later counts the balance error from its start. The scale is the largest total energy
// (initial + work done: LS-DYNA glstat's energy-ratio denominator).
TEST(ExplicitOutput, EnergyHealthOverAJudgedWindow) {
    const fs::path dir = fs::temp_directory_path() / fmt::format("fem_health_window_{}", ::getpid());
    fs::remove_all(dir);
    Mesh mesh = box_hex8(0.1, 0.02, 0.02, 5, 1, 1, "bar");
    auto run = [&](double end, double until, double from = 0.0, std::vector<double> dumps = {}, fs::path restart = {}) {
        auto model = pulled_bar(mesh);
        ExplicitOptions o;
        o.end_time = end;
        o.progress = false;
        o.print_summary = false;
        o.exact_viscous_energy = false;  // a first-order viscous booking: a balance error that grows
        o.health_until = until;
        o.health_from = from;
        o.restart_times = std::move(dumps);
        if (!o.restart_times.empty()) o.restart_dir = dir;
        o.restart_from = restart;
        ExplicitSolver solver(*model, o);
        RunSummary sum = solver.run();
        return std::pair{sum, solver.restart_files()};
    };
    const auto [whole, no_files] = run(2e-4, std::numeric_limits<double>::infinity());
    const auto [longer, files] = run(4e-4, 2e-4, 0.0, {1e-4});
    ASSERT_EQ(files.size(), 1u);
    EXPECT_GT(whole.energy.max_abs_balance_error, 0.0);
    EXPECT_EQ(longer.energy.max_abs_balance_error, whole.energy.max_abs_balance_error);
    EXPECT_EQ(longer.energy.reference, whole.energy.reference);
    EXPECT_EQ(longer.energy.relative_error(), whole.energy.relative_error());
    EXPECT_EQ(longer.energy.hourglass_fraction(), whole.energy.hourglass_fraction());
    EXPECT_NE(longer.energy.kinetic, whole.energy.kinetic);  // (the end state is another)
    // The scale: the largest total energy, at least the final one (here the energies grow).
    EXPECT_GE(whole.energy.reference, whole.energy.total());
    EXPECT_NEAR(whole.energy.reference, whole.energy.initial + whole.energy.external, 0.02 * whole.energy.reference);
    const nlohmann::json j = longer.to_json();
    EXPECT_EQ(j["health_window_s"][1].get<double>(), 2e-4);
    // Restarted at 1e-4 s (inside the window): the same health.
    const auto [restarted, none] = run(4e-4, 2e-4, 0.0, {}, files[0]);
    EXPECT_EQ(restarted.energy.max_abs_balance_error, longer.energy.max_abs_balance_error);
    EXPECT_EQ(restarted.energy.relative_error(), longer.energy.relative_error());
    EXPECT_EQ(restarted.energy.hourglass_fraction(), longer.energy.hourglass_fraction());
    // A window from 2e-4 s: the error made before it does not count.
    const auto [late, unused] = run(4e-4, std::numeric_limits<double>::infinity(), 2e-4);
    const auto [all, unused2] = run(4e-4, std::numeric_limits<double>::infinity());
    fmt::print("balance error: max {:.4g} J to 2e-4 s, {:.4g} J to 4e-4 s, {:.4g} J from 2e-4 s; scale {:.4g} J\n",
               whole.energy.max_abs_balance_error, all.energy.max_abs_balance_error, late.energy.max_abs_balance_error,
               whole.energy.reference);
    EXPECT_EQ(late.energy.balance_error, all.energy.balance_error);  // the same run
    EXPECT_NE(late.energy.max_abs_balance_error, all.energy.max_abs_balance_error);
    EXPECT_THROW(run(4e-4, 1e-4, 2e-4), InputError);  // an empty window
    fs::remove_all(dir);
}
