// Peer benchmark: the wall time of our explicit solver and of CalculiX's *DYNAMIC, EXPLICIT on the
// same models (ccx_explicit.hpp: the bar impact and the Case A rubber finger, 20 ms), one thread
// each, and their ratio. The agreement of the two is the CTest test explicit_peer_ccx
// (peer_ccx_explicit.cpp). The modal side by side is bench_modal.
//   build/bench/bench_peer_ccx
// ccx's time is its whole process (start-up, deck parsing and output included); ours is the solver's
// run() (set-up, including the start-up omega_max measurement, is reported apart as ours_setup_s).
// Wall and CPU times of both: on a shared machine ccx's wall time was ~10 x its CPU time (it writes
// its status and output files as it goes), so the CPU ratio is the fairer one.
#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include "ccx_explicit.hpp"

namespace {

double cpu_self() {
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
double cpu_children() {
    rusage u{};
    getrusage(RUSAGE_CHILDREN, &u);
    return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

void BM_PeerExplicit(benchmark::State& state) {
    using namespace fem::test;
    const PeerModel m = state.range(0) == 0 ? bar_impact() : finger_case_a();
    const auto dir = std::filesystem::temp_directory_path() / "fem_bench_peer_ccx";
    PeerHistory ours, ccx;
    double setup = 0, ours_cpu = 0, ccx_cpu = 0;
    for (auto _ : state) {
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = cpu_self();
        ours = run_ours(m);
        ours_cpu = cpu_self() - c0;  // set-up included
        setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() - ours.wall_s;
        const double cc0 = cpu_children();
        ccx = run_ccx_explicit(m, dir, 0.4 * m.end_time / ours.steps);
        ccx_cpu = cpu_children() - cc0;
        state.SetIterationTime(ours.wall_s + ccx.wall_s);
    }
    std::filesystem::remove_all(dir);
    double l[1] = {0};
    getloadavg(l, 1);
    state.SetLabel(m.name);
    state.counters["ours_s"] = ours.wall_s;
    state.counters["ours_setup_s"] = setup;
    state.counters["ours_steps"] = static_cast<double>(ours.steps);
    state.counters["ccx_s"] = ccx.wall_s;
    state.counters["ccx_steps"] = static_cast<double>(ccx.steps);
    state.counters["ours_cpu_s"] = ours_cpu;
    state.counters["ccx_cpu_s"] = ccx_cpu;
    state.counters["ccx_over_ours"] = ccx.wall_s / ours.wall_s;
    state.counters["ccx_over_ours_cpu"] = ccx_cpu / ours_cpu;
    state.counters["ccx_over_ours_per_step"] = (ccx.wall_s / ccx.steps) / (ours.wall_s / ours.steps);
    state.counters["load1"] = l[0];
}
BENCHMARK(BM_PeerExplicit)->Arg(0)->Arg(1)->ArgName("model")->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
