// Seconds per SIMP/OC iteration and peak memory (issue 16) on the MBB half-beam of the 88-line code
// (Andreassen et al. 2011: volume fraction 0.5, p = 3, r = 1.5 elements, move 0.2): 60 x 20,
// 300 x 100 and 600 x 200 quad4 grids, sensitivity and density filters, direct (CHOLMOD) and
// multigrid-CG solvers; and the thesis-sized shell case, the gripper of Fig 5-6 (40 x 80 MITC4 flat
// shells, three load cases). Targets: 300 x 100 <= 0.06 s and 600 x 200 <= 0.3 s per iteration.
//
// Each case runs the first `iterations` design iterations (the expensive phase for the multigrid:
// the design still moves, so its warm start helps least) in a child process, so that the peak
// resident size (wait4's ru_maxrss) is the case's own. Counters: s_per_iteration (wall),
// cpu_s_per_iteration (the child's CPU time: on a shared machine the wall time also counts other
// jobs), the split of an iteration (assembly, solve, sensitivities, filter, OC update), CG iterations
// per design, peak_rss_MB.
#include <benchmark/benchmark.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <ctime>
#include <string>

#include "mesh/mesh.hpp"
#include "topopt/model.hpp"
#include "topopt/simp.hpp"

using namespace fem;
using namespace fem::topopt;

namespace {

Model mbb(int nx, int ny) {
    const Mesh mesh = rectangle_quads(nx, ny, nx, ny, ElementShape::Quad4);
    Model m = plane_stress_model(mesh, ElasticMaterial::make("unit", 1.0, 0.3, 1.0), 1.0);
    m.fix(mesh.node_sets.at("x0"), {0}, "symmetry edge");
    m.fix(nearest_node(mesh, Vec3(nx, 0, 0)), 1);
    m.add_force(0, nearest_node(mesh, Vec3(0, ny, 0)), Vec3(0, -1, 0));
    return m;
}

// The gripper of thesis Fig 5-6 / Eqs 5-10..5-13 as in studies/topology_cases (step 4).
Model gripper() {
    const Mesh mesh = rectangle_quads(0.05, 0.1, 40, 80, ElementShape::Quad4);
    Model m = shell_model(mesh, ElasticMaterial::make("steel", 210e9, 0.28, 7700), 0.010);
    std::vector<int> corner;
    for (int n = 0; n < mesh.node_count(); ++n)
        if (mesh.nodes[n].y() < 1e-9 && mesh.nodes[n].x() > 0.045 - 1e-9) corner.push_back(n);
    m.fix(corner, {0, 1, 2, 3, 4, 5}, "fixed corner");
    m.add_force(0, nearest_node(mesh, Vec3(0.010, 0.090, 0)), Vec3(-16.2, -6.5, -5.3));
    m.add_force(1, nearest_node(mesh, Vec3(0.015, 0.084, 0)), Vec3(-38, -11.5, -1));
    m.add_force(2, nearest_node(mesh, Vec3(0.020, 0.078, 0)), Vec3(-50.6, -55.3, -22.6));
    return m;
}

enum Quantity { kWall, kCpu, kAssembly, kSolve, kSensitivities, kFilter, kUpdate, kCg, kElements, kCount };

void run(benchmark::State& state, Model (*make)(), FilterKind filter, SolverKind solver, double radius,
         double volume_fraction, int iterations) {
    std::array<double, kCount> q{};
    long peak_kb = 0;
    for (auto _ : state) {
        int fd[2];
        if (pipe(fd) != 0) state.SkipWithError("pipe failed");
        const pid_t pid = fork();
        if (pid == 0) {  // child: build, optimize, report
            close(fd[0]);
            const Model m = make();
            Settings s;
            s.volume_fraction = volume_fraction;
            s.filter = filter;
            s.filter_radius = radius;
            s.solver = solver;
            s.max_iterations = iterations;
            s.change_tolerance = 1e-12;  // run all iterations
            const std::clock_t c0 = std::clock();
            const Result r = optimize(m, s);
            const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
            const double n = r.iterations, loop = r.seconds - r.seconds_setup;
            std::array<double, kCount> out{loop / n, cpu * loop / r.seconds / n, r.timing.assembly / n,
                                           r.timing.solve / n, r.timing.sensitivities / n, r.timing.filter / n,
                                           r.timing.update / n, r.solver_iterations / n, double(m.element_count())};
            const bool ok = write(fd[1], out.data(), sizeof(out)) == sizeof(out);
            _exit(ok ? 0 : 1);
        }
        close(fd[1]);
        const bool got = read(fd[0], q.data(), sizeof(q)) == sizeof(q);
        close(fd[0]);
        int status = 0;
        rusage ru{};
        wait4(pid, &status, 0, &ru);
        if (!got || status != 0) state.SkipWithError("the optimization failed in the child process");
        peak_kb = ru.ru_maxrss;  // kB on Linux
    }
    state.counters["elements"] = q[kElements];
    state.counters["s_per_iteration"] = q[kWall];
    state.counters["cpu_s_per_iteration"] = q[kCpu];
    state.counters["assembly_s"] = q[kAssembly];
    state.counters["solve_s"] = q[kSolve];
    state.counters["sensitivities_s"] = q[kSensitivities];
    state.counters["filter_s"] = q[kFilter];
    state.counters["update_s"] = q[kUpdate];
    state.counters["cg_per_design"] = q[kCg];
    state.counters["peak_rss_MB"] = peak_kb / 1024.0;
}

Model mbb60() { return mbb(60, 20); }
Model mbb300() { return mbb(300, 100); }
Model mbb600() { return mbb(600, 200); }

constexpr int kIterations = 20;

#define MBB_CASE(name, make, filter, solver)                                                                  \
    void BM_##name(benchmark::State& state) { run(state, make, filter, solver, 1.5, 0.5, kIterations); }      \
    BENCHMARK(BM_##name)->Unit(benchmark::kMillisecond)->Iterations(1)

MBB_CASE(Mbb60x20_Sensitivity_Direct, mbb60, FilterKind::Sensitivity, SolverKind::Direct);
MBB_CASE(Mbb60x20_Density_Direct, mbb60, FilterKind::Density, SolverKind::Direct);
MBB_CASE(Mbb60x20_Sensitivity_Multigrid, mbb60, FilterKind::Sensitivity, SolverKind::Multigrid);
MBB_CASE(Mbb60x20_Density_Multigrid, mbb60, FilterKind::Density, SolverKind::Multigrid);
MBB_CASE(Mbb300x100_Sensitivity_Direct, mbb300, FilterKind::Sensitivity, SolverKind::Direct);
MBB_CASE(Mbb300x100_Density_Direct, mbb300, FilterKind::Density, SolverKind::Direct);
MBB_CASE(Mbb300x100_Sensitivity_Multigrid, mbb300, FilterKind::Sensitivity, SolverKind::Multigrid);
MBB_CASE(Mbb300x100_Density_Multigrid, mbb300, FilterKind::Density, SolverKind::Multigrid);
MBB_CASE(Mbb600x200_Sensitivity_Direct, mbb600, FilterKind::Sensitivity, SolverKind::Direct);
MBB_CASE(Mbb600x200_Density_Direct, mbb600, FilterKind::Density, SolverKind::Direct);
MBB_CASE(Mbb600x200_Sensitivity_Multigrid, mbb600, FilterKind::Sensitivity, SolverKind::Multigrid);
MBB_CASE(Mbb600x200_Density_Multigrid, mbb600, FilterKind::Density, SolverKind::Multigrid);

// The whole 300 x 100 optimization against issue 16's reference (the 88-line code under GNU Octave,
// tight bisection): the same iteration count and the compliance to 5e-5 (the stopping tolerance),
// with the solver `auto` picks (multigrid). 30 s (sensitivity) and 60 s (density) of CPU: too long for
// every `make test`, which checks the first 20 iterations against the direct solver instead
// (tests/topopt/test_multigrid.cpp). A mismatch is reported as an error of the benchmark.
void reference_design(benchmark::State& state, FilterKind filter, int iterations, double compliance) {
    for (auto _ : state) {
        Settings s;
        s.volume_fraction = 0.5;
        s.filter = filter;
        s.filter_radius = 1.5;
        s.solver = SolverKind::Automatic;
        const Result r = optimize(mbb300(), s);
        state.counters["iterations"] = r.iterations;
        state.counters["reference_iterations"] = iterations;
        state.counters["compliance"] = r.compliance.back();
        state.counters["reference_compliance"] = compliance;
        state.counters["s_per_iteration"] = r.seconds_per_iteration();
        if (r.solver.find("multigrid") == std::string::npos || !r.converged || r.iterations != iterations ||
            std::abs(r.compliance.back() - compliance) > 5e-5 * compliance)
            state.SkipWithError("the design differs from issue 16's reference (see the counters)");
    }
}
void BM_Mbb300x100_Sensitivity_ReferenceDesign(benchmark::State& state) {
    reference_design(state, FilterKind::Sensitivity, 364, 189.4711);
}
void BM_Mbb300x100_Density_ReferenceDesign(benchmark::State& state) {
    reference_design(state, FilterKind::Density, 837, 195.305);
}
BENCHMARK(BM_Mbb300x100_Sensitivity_ReferenceDesign)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_Mbb300x100_Density_ReferenceDesign)->Unit(benchmark::kMillisecond)->Iterations(1);

// The gripper (thesis Fig 5-6, 90 % removed, filter 1.5 elements of 1.25 mm): 3200 MITC4 shells.
void BM_ThesisGripperShell40x80_Direct(benchmark::State& state) {
    run(state, gripper, FilterKind::Sensitivity, SolverKind::Direct, 1.5 * 0.05 / 40, 0.1, kIterations);
}
BENCHMARK(BM_ThesisGripperShell40x80_Direct)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
