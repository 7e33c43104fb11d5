// Cost of one contact evaluation (search upkeep + projection + forces) for a ball resting on a
// rigid plane and for two deformable blocks pressed together (two-way), at growing surface sizes:
// the time per cycle should grow in proportion to the number of surface nodes.
#include <benchmark/benchmark.h>

#include "ball_mesh.hpp"
#include "contact/contact.hpp"

using namespace fem;
using namespace fem::contact;

static void BM_BallOnPlane(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const double R = 0.05;
    const auto mat = ElasticMaterial::make("soft", 1e7, 0.3, 1000);
    Mesh mesh = fem::test::ball_hex8(R, n, 0.5, 0.5);
    mesh.translate(Vec3(0, 0, R - 0.002));  // pole 2 mm deep: a patch of nodes in contact
    const int n_ball = mesh.node_count();
    mesh.append(parallelogram_quad4(Vec3::Zero(), Vec3(4 * R, 0, 0), Vec3(0, 4 * R, 0), 4 * n, 4 * n, "ground"));
    ContactOptions o;
    o.friction = {0.6, 0.4, 1.0};
    ContactInterface c("ball", ContactSurface::from_part(mesh, "ball", mat),
                       ContactSurface::rigid_part(mesh, "ground", 0.5 * R), o);
    std::vector<Vec3> x = mesh.nodes, v(mesh.node_count(), Vec3::Zero()), f(mesh.node_count());
    for (int i = 0; i < n_ball; ++i) v[i] = Vec3(1e-3, 0, 0);
    double t = 0;
    for (auto _ : state) {
        for (int i = 0; i < n_ball; ++i) x[i].x() += 1e-9;  // a little sliding each cycle
        c.evaluate(x, v, t, 1e-6, f);
        t += 1e-6;
        benchmark::DoNotOptimize(f.data());
    }
    state.counters["surface_nodes"] = static_cast<double>(6 * n * n + 2);
    state.counters["in_contact"] = static_cast<double>(c.contacts().size());
    state.counters["ns_per_node"] = benchmark::Counter(static_cast<double>(6 * n * n + 2),
                                                       benchmark::Counter::kIsIterationInvariantRate |
                                                           benchmark::Counter::kInvert);
}
BENCHMARK(BM_BallOnPlane)->Arg(8)->Arg(16)->Arg(32)->Unit(benchmark::kMicrosecond);

static void BM_TwoBlocksTwoWay(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const auto mat = ElasticMaterial::make("soft", 1e7, 0.3, 1000);
    Mesh mesh = box_hex8(1.0, 1.0, 0.2, n, n, 2, "lower");
    Mesh up = box_hex8(1.0, 1.0, 0.2, n + 1, n + 1, 2, "upper");
    up.translate(Vec3(0, 0, 0.2 - 1e-4));
    mesh.append(up);
    ContactOptions o;
    o.two_way = true;
    ContactInterface c("blocks", ContactSurface::from_part(mesh, "upper", mat), ContactSurface::from_part(mesh, "lower", mat), o);
    std::vector<Vec3> x = mesh.nodes, v(mesh.node_count(), Vec3::Zero()), f(mesh.node_count());
    for (auto _ : state) {
        c.evaluate(x, v, 0.0, 1e-6, f);
        benchmark::DoNotOptimize(f.data());
    }
    state.counters["in_contact"] = static_cast<double>(c.contacts().size());
}
BENCHMARK(BM_TwoBlocksTwoWay)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
