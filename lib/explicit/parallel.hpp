#pragma once
// Fixed partition of loops into chunks whose size does not depend on the number of threads: each
// chunk is summed sequentially and the chunk sums are added in chunk order, so every reduction
// gives the same bits on 1 or N threads (deterministic results, DESIGN.md). Which thread runs a
// chunk does not matter, so chunks may also be scheduled dynamically (Hex8Group does: on a shared
// machine a preempted thread then does not hold the others up).
#include <algorithm>
#include <utility>

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

}  // namespace fem::par
