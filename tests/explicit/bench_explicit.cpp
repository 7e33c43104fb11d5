// Throughput of the explicit solver: the hexahedron internal-force kernel (on ~100,000 hexahedra and
// on a 4,096-element mesh that stays in cache) and whole solver steps on ~100,000 hexahedra, on 1
// and 2 OpenMP threads, in element-cycles per second; the same for ~100,000 Belytschko-Tsay shells;
// and the 100-element wire of thesis Table 2-8 (beams, rotations). Run: build/bench/bench_explicit.
//
// Counters: elem_cycles_per_s (wall clock), elem_cycles_per_cpu_s (per second of process CPU time,
// all threads: the throughput per core actually used, which the other users of a shared machine
// disturb much less than the wall clock), load1 (the 1-minute load average when the case ran: with
// 2 cores, a load above ~1 means the second thread shares its core and the 2-thread wall figures
// say little). Unless OMP_WAIT_POLICY or GOMP_SPINCOUNT is set, the program re-runs itself with
// OMP_WAIT_POLICY=passive: a thread waiting at a barrier then sleeps instead of spinning, which on a
// loaded 2-core machine made 2 threads 3x faster (the spinning thread took the core the late thread
// needed), at a cost of a few microseconds per barrier on an idle one.
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <random>

#include "explicit/parallel.hpp"
#include "explicit_test_support.hpp"
#include "explicit/solver.hpp"

using namespace fem;

namespace {
double cpu_seconds() {  // process CPU time, all threads
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
double load1() {
    double l[1] = {0.0};
    return getloadavg(l, 1) == 1 ? l[0] : -1.0;
}

const ElasticMaterial kRubber = ElasticMaterial::make("rubber", 5e6, 0.49, 1100);
const ElasticMaterial kSteelShell = ElasticMaterial::make("steel", 210e9, 0.28, 7700);

// 50 x 50 x 40 = 100,000 hexahedra.
const Mesh& big_mesh() {
    static const Mesh m = box_hex8(0.5, 0.5, 0.4, 50, 50, 40, "block");
    return m;
}

// 16 x 16 x 16 = 4,096 hexahedra: the working set (~4 MB) stays in cache, so this measures the
// arithmetic; the 100,000-element mesh (~60 MB streamed per cycle) adds the memory traffic.
const Mesh& small_mesh() {
    static const Mesh m = box_hex8(0.16, 0.16, 0.16, 16, 16, 16, "block");
    return m;
}

void BM_Hex8InternalForces(benchmark::State& state) {
    par::set_threads(static_cast<int>(state.range(0)));
    const bool with_dt = state.range(1) != 0;
    const Mesh& mesh = state.range(2) ? small_mesh() : big_mesh();
    Hex8Group g(mesh, 0, kRubber);
    NodalState s;
    s.X = mesh.nodes;
    s.x = mesh.nodes;
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1e-4, 1e-4);
    for (auto& x : s.x) x += Vec3(u(rng), u(rng), u(rng));
    s.v.assign(mesh.node_count(), Vec3::Zero());
    for (auto& v : s.v) v = Vec3(u(rng), u(rng), u(rng));
    s.f.assign(mesh.node_count(), Vec3::Zero());
    const double load = load1();
    const double cpu0 = cpu_seconds();
    for (auto _ : state) {
        auto r = g.internal_forces(s, with_dt);
        benchmark::DoNotOptimize(r);
    }
    const double cpu = cpu_seconds() - cpu0;
    state.SetItemsProcessed(state.iterations() * g.size());
    state.counters["elem_cycles_per_s"] =
        benchmark::Counter(static_cast<double>(g.size()), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["elem_cycles_per_cpu_s"] = static_cast<double>(state.iterations()) * g.size() / cpu;
    state.counters["threads"] = par::threads();
    state.counters["load1"] = load;
}
BENCHMARK(BM_Hex8InternalForces)
    ->Args({1, 1, 0})->Args({2, 1, 0})->Args({1, 0, 0})->Args({2, 0, 0})->Args({1, 1, 1})->Args({2, 1, 1})->Args({1, 0, 1})->Args({2, 0, 1})
    ->ArgNames({"threads", "dt", "small"})->Unit(benchmark::kMillisecond)->UseRealTime();

// Whole solver steps (forces, critical step every cycle, node update, energies) on 100,000 hexahedra.
void BM_SolverSteps(benchmark::State& state) {
    par::set_threads(static_cast<int>(state.range(0)));
    const int steps = 20;
    double cycles_per_s = 0, cycles_per_cpu_s = 0, setup_s = 0, factor = 1;
    const double load = load1();
    for (auto _ : state) {
        ExplicitModel model(big_mesh());
        model.add_hex8("block", kRubber);
        model.fix(big_mesh().node_set("z0"), Dofs::all());
        model.set_initial_velocity([](const Vec3& X) { return Vec3(0.1 * X.z(), 0, 0); });
        ExplicitOptions o;
        o.print_summary = false;
        o.progress = false;
        o.end_time = 1.0;  // replaced below
        o.hex_stability_check = false;
        ExplicitSolver probe(model, o);
        o.end_time = (steps - 0.5) * 0.9 * probe.critical_dt();
        o.hex_stability_check = true;  // the start-up omega_max measurement, timed separately
        const auto t0 = std::chrono::steady_clock::now();
        ExplicitSolver solver(model, o);
        setup_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        factor = solver.stability_factor();
        const double cpu0 = cpu_seconds();
        const RunSummary sum = solver.run();
        const double cpu = cpu_seconds() - cpu0;
        state.SetIterationTime(sum.wall_s);
        cycles_per_s = std::max(cycles_per_s, sum.element_cycles_per_s);  // best of the iterations
        cycles_per_cpu_s = std::max(cycles_per_cpu_s, sum.element_cycles_per_s * sum.wall_s / cpu);
    }
    state.counters["elem_cycles_per_s"] = cycles_per_s;
    state.counters["elem_cycles_per_cpu_s"] = cycles_per_cpu_s;
    state.counters["load1"] = load;
    state.counters["setup_s"] = setup_s;
    state.counters["stability_factor"] = factor;
    state.counters["threads"] = par::threads();
}
BENCHMARK(BM_SolverSteps)->Arg(1)->Arg(2)->ArgName("threads")->UseManualTime()->Unit(benchmark::kMillisecond)
    ->Iterations(2);

// 320 x 320 = 102,400 Belytschko-Tsay shells (explicit/shell_group.hpp), a plate with random small
// displacements, rotations and velocities: the group's internal forces per cycle (node pass for the
// increments, two corotational frames, stress update through the thickness, hourglass, drilling,
// the Table 2-1 step when dt = 1), on 1 and 2 threads.
const Mesh& shell_mesh() {
    static const Mesh m = rectangle_quads(0.32, 0.32, 320, 320, ElementShape::Quad4, "plate");
    return m;
}

void BM_ShellInternalForces(benchmark::State& state) {
    par::set_threads(static_cast<int>(state.range(0)));
    const bool with_dt = state.range(1) != 0;
    const Mesh& mesh = shell_mesh();
    ShellGroup g(mesh, 0, kSteelShell, {.thickness = 1e-3});
    NodalState s = test::state_at_rest(mesh);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1e-6, 1e-6);
    s.rot_index.resize(mesh.node_count());
    for (int i = 0; i < mesh.node_count(); ++i) {
        s.rot_index[i] = i;
        s.rot_node.push_back(i);
    }
    s.omega.assign(mesh.node_count(), Vec3::Zero());
    s.moment.assign(mesh.node_count(), Vec3::Zero());
    s.inertia.assign(mesh.node_count(), 1.0);
    s.rotation.assign(mesh.node_count(), Mat3::Identity());
    g.initialize(s);
    const double load = load1();
    double cpu = 0.0;
    long passes = 0;
    for (auto _ : state) {
        // A fresh small step each pass (the group's increments are against its last evaluation).
        state.PauseTiming();
        for (int i = 0; i < mesh.node_count(); ++i) {
            s.x[i] += Vec3(u(rng), u(rng), u(rng));
            s.rotation[i] = Eigen::AngleAxisd(1e3 * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()) * s.rotation[i];
        }
        state.ResumeTiming();
        const double cpu0 = cpu_seconds();
        auto r = g.internal_forces(s, with_dt);
        cpu += cpu_seconds() - cpu0;
        ++passes;
        benchmark::DoNotOptimize(r);
    }
    state.SetItemsProcessed(state.iterations() * g.size());
    state.counters["elem_cycles_per_s"] =
        benchmark::Counter(static_cast<double>(g.size()), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["elem_cycles_per_cpu_s"] = static_cast<double>(passes) * g.size() / cpu;
    state.counters["threads"] = par::threads();
    state.counters["load1"] = load;
}
BENCHMARK(BM_ShellInternalForces)
    ->Args({1, 1})->Args({2, 1})->Args({1, 0})->Args({2, 0})->ArgNames({"threads", "dt"})
    ->Unit(benchmark::kMillisecond)->UseRealTime();

// Whole solver steps on the 102,400-shell plate, clamped along one edge, started with a velocity
// field: forces, step, node and rotation update, energies. The group's start-up stability
// measurement (Lanczos, ShellGroup::initialize) is timed separately (setup_s).
void BM_ShellSolverSteps(benchmark::State& state) {
    par::set_threads(static_cast<int>(state.range(0)));
    const int steps = 20;
    double cycles_per_s = 0, cycles_per_cpu_s = 0, setup_s = 0;
    const double load = load1();
    for (auto _ : state) {
        ExplicitModel model(shell_mesh());
        model.add_shells("plate", kSteelShell, {.thickness = 1e-3});
        model.fix(shell_mesh().node_set("x0"), Dofs::all());
        model.set_initial_velocity([](const Vec3& X) { return Vec3(0, 0, 0.1 * X.x()); });
        double dt = 1e300;
        for (double d : model.groups()[0]->reference_time_steps()) dt = std::min(dt, d);
        ExplicitOptions o;
        o.print_summary = false;
        o.progress = false;
        o.end_time = (steps - 0.5) * 0.9 * dt;
        const auto t0 = std::chrono::steady_clock::now();
        ExplicitSolver solver(model, o);
        setup_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double cpu0 = cpu_seconds();
        const RunSummary sum = solver.run();
        const double cpu = cpu_seconds() - cpu0;
        state.SetIterationTime(sum.wall_s);
        cycles_per_s = std::max(cycles_per_s, sum.element_cycles_per_s);
        cycles_per_cpu_s = std::max(cycles_per_cpu_s, sum.element_cycles_per_s * sum.wall_s / cpu);
    }
    state.counters["elem_cycles_per_s"] = cycles_per_s;
    state.counters["elem_cycles_per_cpu_s"] = cycles_per_cpu_s;
    state.counters["load1"] = load;
    state.counters["setup_s"] = setup_s;
    state.counters["threads"] = par::threads();
}
BENCHMARK(BM_ShellSolverSteps)->Arg(1)->Arg(2)->ArgName("threads")->UseManualTime()->Unit(benchmark::kMillisecond)
    ->Iterations(2);

// The compliant beam of Table 2-8: 100 beam elements, tip mass, 2000 steps.
void BM_WireSteps(benchmark::State& state) {
    par::set_threads(1);
    double cycles_per_s = 0, us_per_step = 0;
    for (auto _ : state) {
        Mesh mesh = line_beam2(Vec3::Zero(), Vec3(0.4, 0, 0), 100, "beam");
        ExplicitModel model(mesh);
        const int tip = test::add_table_2_8_wire(model, mesh);
        ExplicitOptions o;
        o.print_summary = false;
        o.progress = false;
        o.end_time = 2000 * 0.9 * 0.004 / std::sqrt(209e9 / 7957);
        o.history_nodes = {{"tip", tip}};
        o.history_interval = 1e-4;
        ExplicitSolver solver(model, o);
        const RunSummary sum = solver.run();
        state.SetIterationTime(sum.wall_s);
        cycles_per_s = sum.element_cycles_per_s;
        us_per_step = 1e6 * sum.wall_s / sum.steps;
    }
    state.counters["elem_cycles_per_s"] = cycles_per_s;
    state.counters["us_per_step"] = us_per_step;
}
BENCHMARK(BM_WireSteps)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);
}  // namespace

int main(int argc, char** argv) {
    // See the top: passive waiting at OpenMP barriers unless the user chose a policy. libgomp reads
    // the variable when it is loaded, so the program re-runs itself with it set.
    if (!std::getenv("OMP_WAIT_POLICY") && !std::getenv("GOMP_SPINCOUNT")) {
        setenv("OMP_WAIT_POLICY", "passive", 1);
        execv("/proc/self/exe", argv);  // returns only on failure: then run as we are
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
