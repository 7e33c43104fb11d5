// Benchmark: the first 30 modes of tet10 models of ~10,000, ~100,000 and ~300,000 DOF (a clamped
// 0.4 m x 0.2 m x 0.1 m steel block, hexes split into six tet10 each), ours against CalculiX on the
// same mesh in the same run (issue 17 section 3). Reports wall times and their ratio, peak memory
// (getrusage: ours = this process, ccx = the child) and the largest relative frequency difference.
// Both sides use the 4-point C3D10 mass (ccx's rule, see peer_ccx_modal.cpp) so that the accuracy is
// equal; single thread for both. And the first 30 modes of a ~100,000-DOF MITC4 shell plate (ours).
//   build/bench/bench_modal [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include <sys/resource.h>

#include "assembly/model.hpp"
#include "box_tet10.hpp"
#include "ccx_deck.hpp"
#include "modal/modal.hpp"

namespace {

double peak_mb(int who) {
    rusage u{};
    getrusage(who, &u);
    return u.ru_maxrss / 1024.0;  // ru_maxrss is in kB on Linux
}

double cpu_seconds(int who) {
    rusage u{};
    getrusage(who, &u);
    return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

void BM_Modal30Tet10(benchmark::State& state) {
    const auto steel = fem::ElasticMaterial::make("steel", 210e9, 0.3, 7800.0);
    const int nx = static_cast<int>(state.range(0)), ny = static_cast<int>(state.range(1)), nz = static_cast<int>(state.range(2));
    const fem::Mesh mesh = fem::test::box_tet10(0.4, 0.2, 0.1, nx, ny, nz);
    constexpr int kModes = 30;

    // CalculiX first, while this process is still small: the child's peak RSS then is ccx's own
    // (a child forked from a large process inherits its resident size in ru_maxrss).
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "fem_bench_modal_ccx";
    fem::test::write_ccx_frequency_deck(dir, "block", mesh, steel, mesh.node_set("x0"), kModes);
    const double ccx_cpu0 = cpu_seconds(RUSAGE_CHILDREN);
    const double ccx_s = fem::test::run_ccx(dir, "block");
    const double ccx_peak = peak_mb(RUSAGE_CHILDREN);
    const double ccx_cpu = cpu_seconds(RUSAGE_CHILDREN) - ccx_cpu0;
    const auto f_ccx = fem::test::read_ccx_frequencies(dir / "block.dat");
    std::filesystem::remove_all(dir);

    fem::modal::ModalResult r;
    int equations = 0;
    double assemble_s = 0, total_s = 0;
    const double cpu0 = cpu_seconds(RUSAGE_SELF);
    for (auto _ : state) {
        const auto t0 = std::chrono::steady_clock::now();
        fem::Model model(mesh);
        model.add_solid_part("box", steel, {.tet10_mass_rule = fem::solid::Tet10MassRule::FourPoint});
        model.fix_node_set("x0");
        const fem::AssembledSystem sys = model.assemble();
        assemble_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        equations = sys.size();
        r = fem::modal::solve_modes(sys, {.modes = kModes});
        total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        benchmark::DoNotOptimize(r.eigenvalues.data());
    }
    const double our_cpu = cpu_seconds(RUSAGE_SELF) - cpu0;
    const double our_peak = peak_mb(RUSAGE_SELF);
    double worst = 0;
    for (int k = 0; k < kModes && k < static_cast<int>(f_ccx.size()); ++k)
        worst = std::max(worst, std::abs(r.frequencies_hz(k) / f_ccx[k] - 1));

    state.counters["equations"] = equations;
    state.counters["ours_s"] = total_s;
    state.counters["ours_assemble_s"] = assemble_s;
    state.counters["ours_factor_s"] = r.factor_seconds;
    state.counters["ours_lanczos_s"] = r.solve_seconds;
    state.counters["ours_peak_MB"] = our_peak;
    state.counters["factor_nnz"] = static_cast<double>(r.factor_nonzeros);
    state.counters["ccx_s"] = ccx_s;
    state.counters["ours_over_ccx"] = total_s / ccx_s;
    state.counters["ccx_cpu_s"] = ccx_cpu;
    state.counters["ours_cpu_s"] = our_cpu;
    state.counters["ccx_peak_MB"] = ccx_peak;
    state.counters["max_rel_diff"] = worst;
    state.counters["ccx_modes"] = static_cast<double>(f_ccx.size());
    state.counters["worst_residual"] = r.residuals.maxCoeff();
}
// 14 x 7 x 4, 30 x 16 x 8 and 43 x 22 x 11 cells: ~1e4, ~1e5 and ~3e5 DOF (the counter "equations").
// Increasing sizes: the children's peak memory (the largest so far) is then this size's ccx.
BENCHMARK(BM_Modal30Tet10)->Args({14, 7, 4})->Args({30, 16, 8})->Args({43, 22, 11})->ArgNames({"nx", "ny", "nz"})
    ->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

// The first 30 modes of a ~100,000-DOF MITC4 shell model: a 1.0 m x 0.8 m x 3 mm steel plate,
// 130 x 128 elements (16,899 nodes x 6 DOF = 101,394 DOF), clamped along one short edge: the
// portal frame's element and material at the size the issue asks for.
void BM_Modal30Shell_100kDof(benchmark::State& state) {
    const auto steel = fem::ElasticMaterial::make("steel", 210e9, 0.28, 7700.0);
    const fem::Mesh mesh = fem::rectangle_quads(1.0, 0.8, 130, 128, fem::ElementShape::Quad4, "plate");
    constexpr int kModes = 30;
    fem::modal::ModalResult r;
    int equations = 0;
    double assemble_s = 0, total_s = 0;
    const double cpu0 = cpu_seconds(RUSAGE_SELF);
    for (auto _ : state) {
        const auto t0 = std::chrono::steady_clock::now();
        fem::Model model(mesh);
        model.add_shell_part("plate", 0.003, steel);
        model.fix_node_set("x0");
        const fem::AssembledSystem sys = model.assemble();
        assemble_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        equations = sys.size();
        r = fem::modal::solve_modes(sys, {.modes = kModes});
        total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        benchmark::DoNotOptimize(r.eigenvalues.data());
    }
    state.counters["equations"] = equations;
    state.counters["ours_s"] = total_s;
    state.counters["ours_assemble_s"] = assemble_s;
    state.counters["ours_factor_s"] = r.factor_seconds;
    state.counters["ours_lanczos_s"] = r.solve_seconds;
    state.counters["ours_cpu_s"] = cpu_seconds(RUSAGE_SELF) - cpu0;
    state.counters["ours_peak_MB"] = peak_mb(RUSAGE_SELF);
    state.counters["f1_hz"] = r.frequencies_hz(0);
    state.counters["worst_residual"] = r.residuals.maxCoeff();
}
BENCHMARK(BM_Modal30Shell_100kDof)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
