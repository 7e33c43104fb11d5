// Throughput of the explicit solver: the hexahedron internal-force kernel (on ~100,000 hexahedra and
// on a 4,096-element mesh that stays in cache) and whole solver steps on ~100,000 hexahedra, on 1 and 2 OpenMP threads, in element-cycles per second; and the 100-element
// wire of thesis Table 2-8 (beams, rotations). Run: build/bench/bench_explicit.
// Note: the machine is shared (2 cores, several engineers): numbers vary with the load.
#include <benchmark/benchmark.h>

#include <chrono>
#include <random>

#include "explicit/parallel.hpp"
#include "explicit/solver.hpp"

using namespace fem;

namespace {
const ElasticMaterial kRubber = ElasticMaterial::make("rubber", 5e6, 0.49, 1100);

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
    for (auto _ : state) {
        auto r = g.internal_forces(s, with_dt);
        benchmark::DoNotOptimize(r);
    }
    state.SetItemsProcessed(state.iterations() * g.size());
    state.counters["elem_cycles_per_s"] =
        benchmark::Counter(static_cast<double>(g.size()), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["threads"] = par::threads();
}
BENCHMARK(BM_Hex8InternalForces)
    ->Args({1, 1, 0})->Args({2, 1, 0})->Args({1, 0, 0})->Args({2, 0, 0})->Args({1, 1, 1})->Args({2, 1, 1})->Args({1, 0, 1})->Args({2, 0, 1})
    ->ArgNames({"threads", "dt", "small"})->Unit(benchmark::kMillisecond)->UseRealTime();

// Whole solver steps (forces, critical step every cycle, node update, energies) on 100,000 hexahedra.
void BM_SolverSteps(benchmark::State& state) {
    par::set_threads(static_cast<int>(state.range(0)));
    const int steps = 20;
    double cycles_per_s = 0, setup_s = 0, factor = 1;
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
        const RunSummary sum = solver.run();
        state.SetIterationTime(sum.wall_s);
        cycles_per_s = sum.element_cycles_per_s;
    }
    state.counters["elem_cycles_per_s"] = cycles_per_s;
    state.counters["setup_s"] = setup_s;
    state.counters["stability_factor"] = factor;
    state.counters["threads"] = par::threads();
}
BENCHMARK(BM_SolverSteps)->Arg(1)->Arg(2)->ArgName("threads")->UseManualTime()->Unit(benchmark::kMillisecond)
    ->Iterations(2);

// The compliant beam of Table 2-8: 100 beam elements, tip mass, 2000 steps.
void BM_WireSteps(benchmark::State& state) {
    par::set_threads(1);
    double cycles_per_s = 0, us_per_step = 0;
    for (auto _ : state) {
        Mesh mesh = line_beam2(Vec3::Zero(), Vec3(0.4, 0, 0), 100, "beam");
        const auto steel = ElasticMaterial::make("steel", 209e9, 0.3, 7957);
        ExplicitModel model(mesh);
        model.add_beams("beam", steel, {beam::Section::circular(0.6e-3)});
        const int tip = mesh.node_set("end")[0];
        model.add_point_mass("tip mass", tip, 0.015e-3);
        model.fix(mesh.node_set("start"), Dofs::all());
        model.add_nodal_force({tip}, Vec3(0, -0.003, 0), Curve::pulse(0.0, 0.2));
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

BENCHMARK_MAIN();
