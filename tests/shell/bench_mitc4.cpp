// Speed of the MITC4 element matrices (stiffness + consistent + lumped mass of one warped element):
// the portal frame study computes ~6700 of them per model.
#include <benchmark/benchmark.h>

#include "element/shell_mitc4.hpp"

static void BM_Mitc4Matrices(benchmark::State& state) {
    const auto steel = fem::ElasticMaterial::make("steel", 210e9, 0.28, 7700);
    const std::array<fem::Vec3, 4> x = {fem::Vec3(0, 0, 0), fem::Vec3(0.01, 0.0005, 0.0002),
                                        fem::Vec3(0.011, 0.0095, -0.0003), fem::Vec3(-0.0005, 0.009, 0.0001)};
    for (auto _ : state) {
        auto m = fem::shell::mitc4_matrices(x, 0.003, steel);
        benchmark::DoNotOptimize(m);
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Mitc4Matrices);
BENCHMARK_MAIN();
