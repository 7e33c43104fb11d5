#pragma once
// Fixed partition of loops into chunks whose size does not depend on the number of threads: each
// chunk is summed sequentially and the chunk sums are added in chunk order, so every reduction
// gives the same bits on 1 or N threads (deterministic results, DESIGN.md). Which thread runs a
// chunk does not matter, so chunks may also be scheduled dynamically (Hex8Group does: on a shared
// machine a preempted thread then does not hold the others up).
#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "core/types.hpp"

namespace fem::par {

inline constexpr int kChunk = 512;
/// Loops shorter than this run on one thread: for small models the fork/join (and, on a loaded
/// machine, threads spinning for a core) costs more than the work.
inline constexpr int kParallelMin = 4096;

inline int chunk_count(int n) { return (n + kChunk - 1) / kChunk; }
inline std::pair<int, int> chunk_range(int c, int n) { return {c * kChunk, std::min(n, (c + 1) * kChunk)}; }

/// Number of OpenMP threads in use (1 without OpenMP).
int threads();
/// Sets the number of OpenMP threads (no-op without OpenMP).
void set_threads(int n);

/// Element groups write each element's nodal forces into its own slots (slot e * n + a) and then
/// sum them per node: this map lists, for every node of the group, its slots in increasing order,
/// so the per-node sums have the same bits on any number of threads.
struct NodeScatter {
    std::vector<int> nodes;   // the group's nodes, in increasing index
    std::vector<int> offset;  // nodes.size() + 1 offsets into slot
    std::vector<int> slot;    // element slots touching each node, increasing

    template <std::size_t N>
    static NodeScatter build(const std::vector<std::array<int, N>>& connectivity, int node_count) {
        NodeScatter m;
        std::vector<int> count(node_count, 0), first(node_count, -1);
        for (const auto& c : connectivity)
            for (int a : c) ++count[a];
        m.offset.push_back(0);
        for (int i = 0; i < node_count; ++i)
            if (count[i] > 0) {
                first[i] = static_cast<int>(m.nodes.size());
                m.nodes.push_back(i);
                m.offset.push_back(m.offset.back() + count[i]);
            }
        m.slot.resize(m.offset.back());
        std::vector<int> fill(m.nodes.size(), 0);
        for (std::size_t e = 0; e < connectivity.size(); ++e)
            for (std::size_t a = 0; a < N; ++a) {
                const int k = first[connectivity[e][a]];
                m.slot[m.offset[k] + fill[k]++] = static_cast<int>(e * N + a);
            }
        return m;
    }

    /// f[node] += sum of its slots of `slot_forces`, in the fixed order.
    void add_to(const std::vector<Vec3>& slot_forces, std::vector<Vec3>& f, bool parallel) const {
        const int nn = static_cast<int>(nodes.size());
#pragma omp parallel for schedule(dynamic, kChunk) if (parallel)
        for (int k = 0; k < nn; ++k) {
            Vec3 sum = Vec3::Zero();
            for (int j = offset[k]; j < offset[k + 1]; ++j) sum += slot_forces[slot[j]];
            f[nodes[k]] += sum;
        }
    }
};

}  // namespace fem::par
