// Throughput of the explicit solver, per element type: the internal forces of ~100,000 hexahedra,
// 4-node and 10-node tetrahedra (with the critical step, as every cycle of a run) and whole solver
// steps on the same meshes, on 1 and 2 OpenMP threads; the hexahedron kernel's variants (without
// the step, a 4,096-element mesh that stays in cache); the 100-element wire of thesis Table 2-8
// (beams, rotations); ~100,000 Belytschko-Tsay shells (forces and solver steps); and penalty
// contact per slave node and cycle. The program ends with one table of the rates per type (make
// bench prints it). Run: build/bench/bench_explicit.
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
#include <cstdio>
#include <map>
#include <random>
#include <string>

#include "contact/contact.hpp"
#include "explicit/parallel.hpp"
#include "explicit/tet_groups.hpp"
#include "explicit_test_support.hpp"
#include "explicit/solver.hpp"

using namespace fem;
using namespace fem::test;

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

const ElasticMaterial kSteelShell = ElasticMaterial::make("steel", 210e9, 0.28, 7700);

// The table printed at the end: one row per (what, threads), the last measurement of each.
struct Row {
    double elements = 0, nodes = 0;  // per cycle (contact: slave nodes)
    double per_cpu_s = 0;            // element-cycles (contact: slave-node-cycles) per CPU second
    double per_s = 0;                // the same per wall second
    double load = 0;
};
std::map<std::pair<std::string, int>, Row>& table() {
    static std::map<std::pair<std::string, int>, Row> t;
    return t;
}

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
// ~100,000 elements of each solid type: hex8 50 x 50 x 40; tet4 and tet10 from a 24 x 24 x 29 grid
// split into six tetrahedra per cell (100,224 elements; the tet10 mesh has 1.35 nodes per element,
// Gmsh's finger meshes 1.6). Small: ~4,000 elements (hex8 16 x 16 x 16, tets from 8 x 8 x 10 cells),
// for callgrind's instruction counts (load-independent; its set-up on 100,000 elements takes long).
const char* const kSolidType[] = {"hex8", "tet4", "tet10"};
const Mesh& solid_mesh(int type, bool small = false) {
    static const Mesh tet4 = box_tets(0.24, 0.24, 0.29, 24, 24, 29, ElementShape::Tet4, "block");
    static const Mesh tet10 = box_tets(0.24, 0.24, 0.29, 24, 24, 29, ElementShape::Tet10, "block");
    static const Mesh tet4_small = box_tets(0.08, 0.08, 0.1, 8, 8, 10, ElementShape::Tet4, "block");
    static const Mesh tet10_small = box_tets(0.08, 0.08, 0.1, 8, 8, 10, ElementShape::Tet10, "block");
    if (small) return type == 0 ? small_mesh() : type == 1 ? tet4_small : tet10_small;
    return type == 0 ? big_mesh() : type == 1 ? tet4 : tet10;
}
std::unique_ptr<ElementGroup> solid_group(int type, bool small = false) {
    if (type == 0) return std::make_unique<Hex8Group>(solid_mesh(0, small), 0, kRubber);
    if (type == 1) return std::make_unique<Tet4Group>(solid_mesh(1, small), 0, kRubber);
    return std::make_unique<Tet10Group>(solid_mesh(2, small), 0, kRubber);
}

// Internal forces and the critical step of one group of each type (what every cycle of a run does).
void BM_GroupForces(benchmark::State& state) {
    const int type = static_cast<int>(state.range(0));
    par::set_threads(static_cast<int>(state.range(1)));
    const bool small = state.range(2) != 0;
    const Mesh& mesh = solid_mesh(type, small);
    const auto g = solid_group(type, small);
    NodalState s;
    s.X = mesh.nodes;
    s.x = mesh.nodes;
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1e-4, 1e-4);
    for (auto& x : s.x) x += Vec3(u(rng), u(rng), u(rng));
    s.v.assign(mesh.node_count(), Vec3::Zero());
    for (auto& v : s.v) v = Vec3(u(rng), u(rng), u(rng));
    s.f.assign(mesh.node_count(), Vec3::Zero());
    s.fv.assign(mesh.node_count(), Vec3::Zero());  // the solver's default exact viscous booking
    const double load = load1();
    const double cpu0 = cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    for (auto _ : state) {
        auto r = g->internal_forces(s, true);
        benchmark::DoNotOptimize(r);
    }
    const double cpu = cpu_seconds() - cpu0;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cycles = static_cast<double>(state.iterations()) * g->size();
    state.counters["elem_cycles_per_s"] = cycles / wall;
    state.counters["elem_cycles_per_cpu_s"] = cycles / cpu;
    state.counters["node_cycles_per_cpu_s"] = cycles / cpu * mesh.node_count() / g->size();
    state.counters["load1"] = load;
    table()[{std::string(kSolidType[type]) + (small ? " forces + step, small" : " forces + step"), par::threads()}] =
        Row{static_cast<double>(g->size()), static_cast<double>(mesh.node_count()), cycles / cpu, cycles / wall, load};
}
BENCHMARK(BM_GroupForces)
    ->ArgsProduct({{0, 1, 2}, {1, 2}, {0}})->Args({0, 1, 1})->Args({1, 1, 1})->Args({2, 1, 1})
    ->ArgNames({"type", "threads", "small"})->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK(BM_Hex8InternalForces)
    ->Args({1, 1, 0})->Args({2, 1, 0})->Args({1, 0, 0})->Args({2, 0, 0})->Args({1, 1, 1})->Args({2, 1, 1})->Args({1, 0, 1})->Args({2, 0, 1})
    ->ArgNames({"threads", "dt", "small"})->Unit(benchmark::kMillisecond)->UseRealTime();

// Whole solver steps (forces, critical step every cycle, node update, energies) on the ~100,000
// elements of each solid type, clamped at z = 0 and swinging.
void BM_SolverSteps(benchmark::State& state) {
    const int type = static_cast<int>(state.range(0));
    par::set_threads(static_cast<int>(state.range(1)));
    const Mesh& mesh = solid_mesh(type);
    const int steps = 20;
    double cycles_per_s = 0, cycles_per_cpu_s = 0, setup_s = 0, factor = 1, timers_share = 0, elements_share = 0;
    int elements = 0;
    const double load = load1();
    for (auto _ : state) {
        ExplicitModel model(mesh);
        if (type == 0) model.add_hex8("block", kRubber);
        else add_tets(model, "block", kRubber);
        elements = model.groups().front()->size();
        model.fix(mesh.node_set("z0"), Dofs::all());
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
        timers_share = sum.timing.timer_overhead / sum.wall_s;
        elements_share = sum.timing.elements / sum.wall_s;
    }
    state.counters["timers_share"] = timers_share;      // the timing table's own clock reads
    state.counters["elements_share"] = elements_share;  // element forces in the timing table
    state.counters["elem_cycles_per_s"] = cycles_per_s;
    state.counters["elem_cycles_per_cpu_s"] = cycles_per_cpu_s;
    state.counters["load1"] = load;
    state.counters["setup_s"] = setup_s;
    state.counters["stability_factor"] = factor;
    state.counters["threads"] = par::threads();
    table()[{std::string(kSolidType[type]) + " solver step", par::threads()}] =
        Row{static_cast<double>(elements), static_cast<double>(mesh.node_count()), cycles_per_cpu_s, cycles_per_s, load};
}
BENCHMARK(BM_SolverSteps)->ArgsProduct({{0, 1, 2}, {1, 2}})->ArgNames({"type", "threads"})->UseManualTime()
    ->Unit(benchmark::kMillisecond)->Iterations(2);

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
    double cpu = 0.0, wall = 0.0;
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
        const auto t0 = std::chrono::steady_clock::now();
        auto r = g.internal_forces(s, with_dt);
        cpu += cpu_seconds() - cpu0;
        wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        ++passes;
        benchmark::DoNotOptimize(r);
    }
    state.SetItemsProcessed(state.iterations() * g.size());
    state.counters["elem_cycles_per_s"] =
        benchmark::Counter(static_cast<double>(g.size()), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["elem_cycles_per_cpu_s"] = static_cast<double>(passes) * g.size() / cpu;
    state.counters["threads"] = par::threads();
    state.counters["load1"] = load;
    if (with_dt) {
        const double cycles = static_cast<double>(passes) * g.size();
        table()[{"shell BT forces + step", par::threads()}] =
            Row{static_cast<double>(g.size()), static_cast<double>(mesh.node_count()), cycles / cpu, cycles / wall, load};
    }
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
    table()[{"shell BT solver step", par::threads()}] = Row{static_cast<double>(shell_mesh().element_count()),
                                                           static_cast<double>(shell_mesh().node_count()),
                                                           cycles_per_cpu_s, cycles_per_s, load};
}
BENCHMARK(BM_ShellSolverSteps)->Arg(1)->Arg(2)->ArgName("threads")->UseManualTime()->Unit(benchmark::kMillisecond)
    ->Iterations(2);

// The compliant beam of Table 2-8: 100 beam elements, tip mass, 2000 steps.
void BM_WireSteps(benchmark::State& state) {
    par::set_threads(1);
    double cycles_per_s = 0, cycles_per_cpu_s = 0, us_per_step = 0, timers_share = 0;
    const double load = load1();
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
        const double cpu0 = cpu_seconds();
        const RunSummary sum = solver.run();
        const double cpu = cpu_seconds() - cpu0;
        state.SetIterationTime(sum.wall_s);
        cycles_per_s = sum.element_cycles_per_s;
        cycles_per_cpu_s = sum.element_cycles_per_s * sum.wall_s / cpu;
        us_per_step = 1e6 * sum.wall_s / sum.steps;
        timers_share = sum.timing.timer_overhead / sum.wall_s;
    }
    state.counters["elem_cycles_per_s"] = cycles_per_s;
    state.counters["elem_cycles_per_cpu_s"] = cycles_per_cpu_s;
    state.counters["us_per_step"] = us_per_step;
    table()[{"beam solver step (Table 2-8 wire)", 1}] = Row{100, 101, cycles_per_cpu_s, cycles_per_s, load};
    state.counters["timers_share"] = timers_share;  // a small model (17 us per step): the worst case
}
BENCHMARK(BM_WireSteps)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);

// Penalty contact (search upkeep, projection, forces, friction) per slave node and cycle: a 32 x 32
// hexahedral block pressed 0.1 mm into a 31 x 31 one, two-way (both surfaces are slaves in turn).
void BM_ContactPerSlaveNode(benchmark::State& state) {
    par::set_threads(1);
    const int n = 32;
    const auto mat = ElasticMaterial::make("soft", 1e7, 0.3, 1000);
    Mesh mesh = box_hex8(1.0, 1.0, 0.2, n - 1, n - 1, 2, "lower");
    Mesh up = box_hex8(1.0, 1.0, 0.2, n, n, 2, "upper");
    up.translate(Vec3(0, 0, 0.2 - 1e-4));
    mesh.append(up);
    contact::ContactOptions o;
    o.two_way = true;
    o.friction = {0.6, 0.4, 1.0};
    const auto upper = contact::ContactSurface::from_part(mesh, "upper", mat);
    const auto lower = contact::ContactSurface::from_part(mesh, "lower", mat);
    const double slaves = static_cast<double>(upper.nodes.size() + lower.nodes.size());
    contact::ContactInterface c("blocks", upper, lower, o);
    std::vector<Vec3> x = mesh.nodes, v(mesh.node_count(), Vec3(1e-3, 0, 0)), f(mesh.node_count());
    const double load = load1();
    const double cpu0 = cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    double t = 0;
    for (auto _ : state) {
        for (int i = 0; i < up.node_count(); ++i) x[mesh.node_count() - 1 - i].x() += 1e-9;  // the upper block slides
        c.evaluate(x, v, t, 1e-6, f);
        t += 1e-6;
        benchmark::DoNotOptimize(f.data());
    }
    const double cpu = cpu_seconds() - cpu0;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double node_cycles = slaves * static_cast<double>(state.iterations());
    state.counters["slave_nodes"] = slaves;
    state.counters["in_contact"] = static_cast<double>(c.contacts().size());
    state.counters["ns_per_slave_node_cycle"] = 1e9 * cpu / node_cycles;
    table()[{"contact, per slave node (two-way)", 1}] = Row{slaves, slaves, node_cycles / cpu, node_cycles / wall, load};
}
BENCHMARK(BM_ContactPerSlaveNode)->Unit(benchmark::kMicrosecond);

// The table of make bench: rates per CPU second (the shared machine disturbs them less than the wall
// clock; wall rates and the load average beside them).
void print_table() {
    if (table().empty()) return;
    std::printf("\nExplicit solver throughput per type (per CPU second; ns = CPU ns per element-cycle, or per\n"
                "slave-node-cycle for contact; 'x hex8' = cost per element-cycle and per node-cycle over the hex8\n"
                "row of the same kind on the same number of threads):\n");
    std::printf("%-36s %3s %8s %8s %12s %8s %12s %15s %6s\n", "what", "thr", "elements", "nodes", "M cycles/s", "ns",
                "M wall/s", "x hex8 el/node", "load");
    for (const auto& [key, r] : table()) {
        const auto& [what, threads] = key;
        std::string ratio = "";
        const std::string kind = what.find("solver") != std::string::npos ? "hex8 solver step"
                                 : what.find("small") != std::string::npos ? "hex8 forces + step, small"
                                                                            : "hex8 forces + step";
        const auto ref = table().find({kind, threads});
        if (ref != table().end() && what.rfind("contact", 0) != 0 && ref->second.per_cpu_s > 0) {
            const double per_el = ref->second.per_cpu_s / r.per_cpu_s;
            const double per_node = per_el * (r.elements / r.nodes) / (ref->second.elements / ref->second.nodes);
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.2f / %.2f", per_el, per_node);
            ratio = buf;
        }
        std::printf("%-36s %3d %8.0f %8.0f %12.2f %8.1f %12.2f %15s %6.2f\n", what.c_str(), threads, r.elements,
                    r.nodes, 1e-6 * r.per_cpu_s, 1e9 / r.per_cpu_s, 1e-6 * r.per_s, ratio.c_str(), r.load);
    }
}
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
    print_table();
    benchmark::Shutdown();
    return 0;
}
