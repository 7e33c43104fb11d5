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

/// body(i) for i = 0 .. n-1: statically scheduled over the OpenMP threads when `parallel`, else a
/// plain loop. The plain loop enters no OpenMP region at all: `#pragma omp parallel if (false)`
/// still sets up a one-thread team and ends it with a futex system call, which on this machine's
/// VM (PVM: every system call goes through the hypervisor) cost 5-9 % of a small model's cycle.
template <class Body>
void for_each_index(int n, bool parallel, const Body& body) {
    if (!parallel) {
        for (int i = 0; i < n; ++i) body(i);
        return;
    }
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) body(i);
}

/// Number of OpenMP threads in use (1 without OpenMP).
int threads();
/// Sets the number of OpenMP threads (no-op without OpenMP).
void set_threads(int n);

/// Locality order of elements: the permutation that sorts the elements by their smallest node
/// index (stable). The per-cycle loops then walk the nodal arrays (which are in node order) nearly
/// sequentially, which the hardware prefetcher follows, and consecutive elements share nodes that
/// are still in cache. (Measured on the 100,000-element box: a Morton order of the element
/// centroids was 1.5x slower than this, its node accesses jumping between the node layers.)
template <std::size_t N>
std::vector<int> node_order(const std::vector<std::array<int, N>>& connectivity) {
    const int n = static_cast<int>(connectivity.size());
    std::vector<int> order(n), key(n);
    for (int e = 0; e < n; ++e) {
        order[e] = e;
        key[e] = *std::min_element(connectivity[e].begin(), connectivity[e].end());
    }
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
    return order;
}

/// Colouring of the fixed chunks of a group's (ordered) elements for a direct, deterministic
/// scatter of element forces into the nodal forces: two chunks of one colour share no node. The
/// chunks of a colour can then run in parallel, each adding its elements' forces straight into
/// f[node] in element order, with a barrier between colours. Each node thus receives its
/// contributions in a fixed order - colour, then element, then the element's node order -
/// whatever the number of threads or the schedule: the same bits on 1 or N threads, without
/// per-element force slots gathered back per node (their memory traffic was 16 % of a hexahedron
/// cycle; README.md).
struct ChunkColouring {
    int chunk = 0;                          // elements per chunk
    int elements = 0;
    std::vector<std::vector<int>> colours;  // the chunks of each colour, increasing

    int chunk_count() const { return (elements + chunk - 1) / chunk; }
    std::pair<int, int> range(int c) const { return {c * chunk, std::min(elements, (c + 1) * chunk)}; }

    /// Greedy colouring of the chunk conflict graph in chunk order; among the colours a chunk may
    /// take, the one with the fewest chunks so far (balanced colours: each needs enough chunks to
    /// keep every thread busy).
    template <std::size_t N>
    static ChunkColouring build(const std::vector<std::array<int, N>>& connectivity, int node_count, int chunk) {
        ChunkColouring m;
        m.chunk = chunk;
        m.elements = static_cast<int>(connectivity.size());
        const int nc = m.chunk_count();
        // Chunks touching each node (appended in increasing chunk order, duplicates skipped).
        std::vector<std::vector<int>> node_chunks(node_count);
        for (int c = 0; c < nc; ++c) {
            const auto [e0, e1] = m.range(c);
            for (int e = e0; e < e1; ++e)
                for (int a : connectivity[e]) {
                    auto& v = node_chunks[a];
                    if (v.empty() || v.back() != c) v.push_back(c);
                }
        }
        std::vector<int> colour(nc, -1), stamp;
        std::vector<int> size;
        for (int c = 0; c < nc; ++c) {
            stamp.assign(size.size(), 0);  // stamp[k] = 1: colour k taken by a neighbour
            const auto [e0, e1] = m.range(c);
            for (int e = e0; e < e1; ++e)
                for (int a : connectivity[e])
                    for (int o : node_chunks[a])
                        if (o != c && colour[o] >= 0) stamp[colour[o]] = 1;
            int best = -1;
            for (int k = 0; k < static_cast<int>(size.size()); ++k)
                if (!stamp[k] && (best < 0 || size[k] < size[best])) best = k;
            if (best < 0) {
                best = static_cast<int>(size.size());
                size.push_back(0);
                m.colours.emplace_back();
            }
            colour[c] = best;
            ++size[best];
            m.colours[best].push_back(c);
        }
        return m;
    }

    /// Runs body(chunk) for every chunk, colour by colour (a barrier between colours), on the
    /// OpenMP threads when `parallel`. Inside a colour the chunks are scheduled dynamically: a
    /// chunk's results do not depend on which thread computes it, so the bits are the same on any
    /// number of threads, and a thread that a shared machine preempts does not hold the others up
    /// within a colour.
    template <class Body>
    void for_each_chunk(bool parallel, const Body& body) const {
        if (!parallel) {  // no OpenMP region (see for_each_index); the same order as one thread's
            for (const auto& list : colours)
                for (int c : list) body(c);
            return;
        }
#pragma omp parallel
        {
            const int n_colours = static_cast<int>(colours.size());
            for (int k = 0; k < n_colours; ++k) {
                const auto& list = colours[k];
                const int m = static_cast<int>(list.size());
                if (k + 1 < n_colours) {
#pragma omp for schedule(dynamic, 1)
                    for (int i = 0; i < m; ++i) body(list[i]);
                } else {  // the end of the parallel region is the last barrier
#pragma omp for schedule(dynamic, 1) nowait
                    for (int i = 0; i < m; ++i) body(list[i]);
                }
            }
        }
    }
};

}  // namespace fem::par
