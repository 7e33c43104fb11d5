// Cost of the football sweep (thesis Sec 4.2, studies/football_sweep): one Table 4-4 case (Case 4)
// over 60 ms of its contact window (1.04-1.10 s: the first finger touches the football at ~1.06 s),
// the whole model (5 fingers, half football, pallet, drum; ~3,460 hexahedra) on one thread, as the
// study runs each case. Counters: element-cycles per second of the whole solver step and the
// contact share of the step time.
#include <benchmark/benchmark.h>

#include "explicit/parallel.hpp"
#include "explicit/solver.hpp"
#include "hand/football.hpp"

using namespace fem;

static void BM_FootballCase4Window(benchmark::State& state) {
    par::set_threads(1);
    const auto cases = hand::football::table_4_4();
    for (auto _ : state) {
        hand::football::Options o;
        o.start = 1.04;
        hand::HandModel hm(hand::football::scene(cases[3], o));
        ExplicitOptions opt;
        opt.end_time = 0.06;
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
BENCHMARK(BM_FootballCase4Window)->Iterations(1)->Unit(benchmark::kSecond);

BENCHMARK_MAIN();
