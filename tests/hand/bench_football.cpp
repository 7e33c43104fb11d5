// Cost of the football sweep (thesis Sec 4.2, studies/football_sweep): Table 4-4 Case 4, the whole
// model (5 fingers, half football, pallet, drum; ~3,460 hexahedra) on one thread, as the study runs
// each case (the solver's default settings, histories every 1 ms; the study books viscous work
// first-order, ~15 % faster).
// Its model is lib/hand/football.hpp's, which test ExplicitCase.FootballCaseFileBuildsTheStudysModel
// holds equal bit for bit to studies/football_sweep/football_sweep.toml (what fem-explicit runs).
//   BM_FootballCase4Window: 60 ms of its contact window (1.04-1.10 s: the first finger touches the
//     football at ~1.06 s); seconds.
//   BM_FootballCase4Full: the whole case, t = 0 to the thesis's 3 s (issue 11: "a benchmark in make
//     bench times one full football case"); 470 s of CPU, 817,938 steps (studies/football_sweep/
//     README.md "Files and switches"). Only this one: build/bench/bench_football --benchmark_filter=Full
// Counters: element-cycles per second of the whole solver step and the contact share of the step time.
#include <benchmark/benchmark.h>

#include "explicit/parallel.hpp"
#include "explicit/solver.hpp"
#include "hand/football.hpp"

using namespace fem;

namespace {

void run_case_4(benchmark::State& state, double start, double end) {
    par::set_threads(1);
    const auto cases = hand::football::table_4_4();
    for (auto _ : state) {
        hand::HandModel hm(hand::seen_from(hand::football::scene(cases[3]), start));
        ExplicitOptions opt;
        opt.end_time = end - start;
        opt.print_summary = false;
        opt.progress = false;
        opt.history_interval = 1e-3;
        ExplicitSolver solver(hm.model(), opt);
        const RunSummary s = solver.run();
        state.counters["element_cycles_per_s"] = s.element_cycles_per_s;
        state.counters["contact_share"] = (s.timing.contact_search + s.timing.contact_forces) / s.wall_s;
        state.counters["steps"] = static_cast<double>(s.steps);
        state.counters["dt_us"] = 1e6 * s.min_dt;
    }
}

void BM_FootballCase4Window(benchmark::State& state) { run_case_4(state, 1.04, 1.10); }
void BM_FootballCase4Full(benchmark::State& state) { run_case_4(state, 0.0, 3.0); }

}  // namespace

BENCHMARK(BM_FootballCase4Window)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(BM_FootballCase4Full)->Iterations(1)->Unit(benchmark::kSecond);

BENCHMARK_MAIN();
