#pragma once
// The gather of the explicit solid kernels (hex8::gather, tet::gather): the nodal coordinates x,
// displacements u = x - X and velocities v of kLanes elements into lanes, component i of node a of
// lane l at [i][a][l]. One implementation for every element: N nodes per element, the current
// coordinates of the first NX of them (the hexahedron needs all 8 for its Table 2-1 length, the
// tetrahedra their 4 corners). Data movement and one IEEE subtraction: the same bits on every path.
// Spare lanes (lanes < kLanes in the last block) repeat the last element.
#include <algorithm>
#include <array>
#include <cstddef>

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif

#include "element/hex8_explicit.hpp"

namespace fem::hex8 {

namespace lane_gather_detail {
template <int N, int NX>
void gather_scalar(const double* xs, const double* Xs, const double* vs, const std::array<int, N>* conn, int lanes,
                   Lanes (&x)[3][NX], Lanes (&u)[3][N], Lanes (&v)[3][N]) {
    // Scalar stores into the lanes (on 100,000 hexahedra this keeps more node loads in flight than
    // assembling each vector in registers with generic code, which was 10 % slower there).
    for (int l = 0; l < kLanes; ++l) {
        const auto& cn = conn[std::min(l, lanes - 1)];
        for (int a = 0; a < N; ++a) {
            const std::size_t o = 3 * static_cast<std::size_t>(cn[a]);
            for (int i = 0; i < 3; ++i) {
                u[i][a][l] = xs[o + i] - Xs[o + i];
                v[i][a][l] = vs[o + i];
            }
            if (a < NX)
                for (int i = 0; i < 3; ++i) x[i][a][l] = xs[o + i];
        }
    }
}

#if defined(__GNUC__) && defined(__x86_64__)
// GCC 12's AVX-512 intrinsics start from an undefined vector (self-initialised): a false -Wuninitialized.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
// AVX-512 (with VL): node a's (x, y, z) triples of the eight lanes (offsets o[l * stride] into p) are
// loaded as 256-bit vectors masked to three doubles (no read past a node array's end), lanes k and
// k + 4 in one register, and transposed in registers into the three component vectors.
[[gnu::target("avx512f,avx512vl")]] inline void transpose_triples(const double* p, const std::size_t* o, int stride,
                                                                   __m512d (&out)[3]) {
    const __m512i lo = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13), hi = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
    __m512d z[4];
    for (int k = 0; k < 4; ++k)
        z[k] = _mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_maskz_loadu_pd(0x7, p + o[k * stride])),
                                  _mm256_maskz_loadu_pd(0x7, p + o[(k + 4) * stride]), 1);
    // [x0 x1 z0 z1 | x4 x5 z4 z5], [y0 y1 . . | y4 y5 . .] and the same for lanes 2, 3, 6, 7.
    const __m512d xz01 = _mm512_unpacklo_pd(z[0], z[1]), yw01 = _mm512_unpackhi_pd(z[0], z[1]);
    const __m512d xz23 = _mm512_unpacklo_pd(z[2], z[3]), yw23 = _mm512_unpackhi_pd(z[2], z[3]);
    out[0] = _mm512_permutex2var_pd(xz01, lo, xz23);
    out[1] = _mm512_permutex2var_pd(yw01, lo, yw23);
    out[2] = _mm512_permutex2var_pd(xz01, hi, xz23);
}

template <int N, int NX>
[[gnu::target("avx512f,avx512vl")]] void gather_avx512(const double* xs, const double* Xs, const double* vs,
                                                        const std::array<int, N>* conn, int lanes, Lanes (&x)[3][NX],
                                                        Lanes (&u)[3][N], Lanes (&v)[3][N]) {
    static_assert(kLanes == 8, "eight lanes per AVX-512 vector");
    std::size_t o[kLanes][N];
    for (int l = 0; l < kLanes; ++l) {
        const auto& c = conn[std::min(l, lanes - 1)];
        for (int a = 0; a < N; ++a) o[l][a] = 3 * static_cast<std::size_t>(c[a]);
    }
    for (int a = 0; a < N; ++a) {
        __m512d xa[3], Xa[3], va[3];
        transpose_triples(xs, &o[0][a], N, xa);
        transpose_triples(Xs, &o[0][a], N, Xa);
        transpose_triples(vs, &o[0][a], N, va);
        for (int i = 0; i < 3; ++i) {
            if (a < NX) _mm512_store_pd(reinterpret_cast<double*>(&x[i][a]), xa[i]);
            _mm512_store_pd(reinterpret_cast<double*>(&u[i][a]), _mm512_sub_pd(xa[i], Xa[i]));
            _mm512_store_pd(reinterpret_cast<double*>(&v[i][a]), va[i]);
        }
    }
}
#pragma GCC diagnostic pop
#endif
}  // namespace lane_gather_detail

/// x [3][NX], u and v [3][N] of the kLanes elements conn[0 .. lanes) (AVX-512 when the processor has
/// it, chosen once; scalar otherwise).
template <int N, int NX>
void gather_lanes(const double* xs, const double* Xs, const double* vs, const std::array<int, N>* conn, int lanes,
                  Lanes (&x)[3][NX], Lanes (&u)[3][N], Lanes (&v)[3][N]) {
    static_assert(NX <= N, "the current coordinates of at most every node");
#if defined(__GNUC__) && defined(__x86_64__)
    static const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
    if (avx512) return lane_gather_detail::gather_avx512<N, NX>(xs, Xs, vs, conn, lanes, x, u, v);
#endif
    lane_gather_detail::gather_scalar<N, NX>(xs, Xs, vs, conn, lanes, x, u, v);
}

}  // namespace fem::hex8
