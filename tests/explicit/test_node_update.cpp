// The vectorized central-difference node update (explicit/node_update.cpp) against its scalar
// reference, node by node: the same velocities, positions and energy sums to the bit, on nodes of
// every kind (free, undamped, massless, fixed, prescribed, with and without contact force), over
// lengths that are not a multiple of its block.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "explicit/node_update.hpp"

namespace fem::explicit_detail {
namespace {

struct Nodes {
    std::vector<double> mass, alpha;
    std::vector<unsigned> fixed;
    std::vector<int> target_index;
    std::vector<std::array<double, 3>> target;
    std::vector<Vec3> f, fext, fprov, fv, v, x;

    NodeUpdateData data(bool loads, bool providers, bool viscous) {
        NodeUpdateData d;
        d.mass = mass.data(), d.alpha = alpha.data(), d.fixed = fixed.data();
        d.target_index = target_index.data(), d.target = target.data();
        d.f = f.data(), d.fext = fext.data(), d.fprov = fprov.data(), d.fv = fv.data();
        d.v = v.data(), d.x = x.data();
        d.loads = loads, d.providers = providers, d.book_viscous = viscous;
        d.dtavg = 3.7e-6, d.dt_half = 3.9e-6;
        return d;
    }
};

Nodes random_nodes(int n, unsigned seed) {
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    auto vec = [&](double s) { return Vec3(s * u(gen), s * u(gen), s * u(gen)); };
    Nodes s;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (int i = 0; i < n; ++i) {
        const int kind = static_cast<int>(gen() % 10);
        s.mass.push_back(kind == 0 ? 0.0 : 1e-4 * (1.5 + u(gen)));           // 0: a rigid part's node
        s.alpha.push_back(kind % 3 == 1 ? 0.0 : 200.0 * (1.0 + u(gen)));     // some undamped
        s.fixed.push_back(kind == 2 ? 4u : kind == 3 ? 7u : 0u);             // a symmetry plane, clamped
        if (kind == 0 || kind == 4) {                                         // prescribed (a root, a drum node)
            s.target_index.push_back(static_cast<int>(s.target.size()));
            s.target.push_back({u(gen), kind == 4 ? nan : u(gen), u(gen)});
        } else {
            s.target_index.push_back(-1);
        }
        s.f.push_back(vec(5.0));
        s.fext.push_back(kind == 5 ? Vec3::Zero() : vec(1e-3));
        s.fprov.push_back(kind % 2 ? Vec3::Zero() : vec(2.0));              // contact on some nodes
        s.fv.push_back(vec(0.1));
        s.v.push_back(vec(0.5));
        s.x.push_back(vec(0.2));
    }
    return s;
}

std::uint64_t bits(double a) { return std::bit_cast<std::uint64_t>(a); }

TEST(ExplicitNodeUpdate, VectorizedUpdateEqualsTheScalarReferenceBitForBit) {
    for (const int n : {1, 63, 64, 65, 200, 1000})
        for (const bool loads : {false, true})
            for (const bool providers : {false, true})
                for (const bool viscous : {false, true}) {
                    Nodes a = random_nodes(n, 17u + n), b = a;
                    // Over a chunk that starts inside the arrays, as the solver's chunks do.
                    const int i0 = n > 1 ? 1 : 0;
                    const NodeSums fast = update_nodes(a.data(loads, providers, viscous), i0, n);
                    NodeSums ref;
                    const NodeUpdateData d = b.data(loads, providers, viscous);
                    for (int i = i0; i < n; ++i) update_node(d, i, ref);
                    for (int i = 0; i < n; ++i)
                        for (int k = 0; k < 3; ++k) {
                            ASSERT_EQ(bits(a.v[i][k]), bits(b.v[i][k])) << "n " << n << " node " << i;
                            ASSERT_EQ(bits(a.x[i][k]), bits(b.x[i][k])) << "n " << n << " node " << i;
                        }
                    for (auto [p, q] : {std::pair{fast.ke, ref.ke}, {fast.ke_plus, ref.ke_plus}, {fast.damp, ref.damp},
                                        {fast.wext, ref.wext}, {fast.wabs, ref.wabs}, {fast.damp_half, ref.damp_half},
                                        {fast.wext_half, ref.wext_half}, {fast.wprov, ref.wprov},
                                        {fast.wprov_half, ref.wprov_half}, {fast.visc, ref.visc},
                                        {fast.visc_half, ref.visc_half}})
                        EXPECT_EQ(bits(p), bits(q)) << "n " << n << " loads " << loads << " providers " << providers;
                    EXPECT_EQ(fast.bad, ref.bad);
                    EXPECT_NE(ref.damp, 0.0);
                }
}

}  // namespace
}  // namespace fem::explicit_detail
