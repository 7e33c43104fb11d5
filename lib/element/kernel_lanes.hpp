#pragma once
// What the explicit element kernels (element/hex8_explicit.cpp, tet_explicit.cpp,
// beam_corotational.cpp) share: the lane helpers, and for the solids the material point (neo-Hookean
// stress, stored energy, von Mises, bulk viscosity and stiffness damping from the displacement and
// velocity gradients): one piece of code for every solid element. Included only by those .cpp
// files, which it compiles with fp-contract=off (below).
//
// Every function is a template on T = double (one element) or hex8::Lanes (hex8::kLanes elements,
// one per lane) and does per lane exactly the operations of the scalar version, in the same order:
// element-wise IEEE arithmetic, no reassociation, no FMA contraction. Batching elements therefore
// changes no bit, and the kernels give the same bits on every instruction set they are cloned for.
#include <bit>
#include <cmath>

#include "element/hex8_explicit.hpp"

#if defined(__GNUC__) && !defined(__clang__)
// The Lanes helpers pass eight-double vectors by value; they are internal (inlined into the
// kernels), so the psABI note about AVX vector arguments concerns no interface.
#pragma GCC diagnostic ignored "-Wpsabi"
// No a * b + c contracted into an FMA (GCC's default is -ffp-contract=fast, and the AVX-512 clones
// have FMA): every version of a kernel then gives the same bits.
#pragma GCC optimize("fp-contract=off")
#endif

// The block functions of the kernels are compiled for AVX-512, AVX2 and baseline x86-64 and the
// loader picks the best one the processor supports (GCC function multi-versioning): AVX-512 does a
// Lanes operation in one instruction (AVX2 in two, SSE2 in four), with three-operand forms and 32
// vector registers. FMA is not used (fp-contract=off above), so every version gives the same bits.
// (GCC only: clang 14 refuses the AVX-512 clone calling the baseline inline helpers with 64-byte
// vectors, "changes the ABI"; the clang builds, `make fuzz`, keep the baseline version.)
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__AVX512F__)
#define FEM_KERNEL_CLONES [[gnu::target_clones("avx512f", "avx2", "default")]]
#else
#define FEM_KERNEL_CLONES
#endif

namespace fem::lanes {

using hex8::kLanes;
using hex8::Lanes;

// Lane-wise helpers. Library functions without a vector version are applied lane by lane.
inline double select(bool m, double a, double b) { return m ? a : b; }
template <class M>
inline Lanes select(M m, Lanes a, Lanes b) {
    return m ? a : b;
}
// Whether any lane's mask is set.
inline bool any(bool m) { return m; }
template <class M>
inline bool any(M m) {
    bool r = false;
    for (int l = 0; l < kLanes; ++l) r = r || m[l] != 0;
    return r;
}

// ln(1 + x) in plain arithmetic and bit operations that vectorize (libm's log1p is a scalar call
// per lane). The classic argument reduction and polynomial (fdlibm/FreeBSD log1p; the error bound
// of that method is below 1 ulp; measured here against std::log1p, tests/explicit):
//   u = fl(1 + x) = 2^k m with m in [sqrt(2)/2, sqrt(2)), c = the rounding error of u over u
//   (so ln(1 + x) = ln u + c to first order), f = m - 1 (f = x, c = 0 when k = 0: then nothing
//   is rounded), s = f / (2 + f), ln(1 + f) = f - f^2/2 + s (f^2/2 + R(s^2)) with the minimax
//   polynomial R, and ln 2 split in a high part (exact times k) and a low part.
// Valid for x > -1 (J > 0); other x give NaN or garbage, which the caller discards (inverted).
using LaneBits = long long __attribute__((vector_size(64)));
inline long long bits_of(double x) { return std::bit_cast<long long>(x); }
inline LaneBits bits_of(const Lanes& x) { return reinterpret_cast<const LaneBits&>(x); }
inline double double_of(long long b) { return std::bit_cast<double>(b); }
inline Lanes double_of(const LaneBits& b) { return reinterpret_cast<const Lanes&>(b); }
template <class T>
inline T log1p_lanes(const T& x) {
    constexpr double kLg1 = 6.666666666666735130e-01, kLg2 = 3.999999999940941908e-01,
                     kLg3 = 2.857142874366239149e-01, kLg4 = 2.222219843214978396e-01,
                     kLg5 = 1.818357216161805012e-01, kLg6 = 1.531383769920937332e-01,
                     kLg7 = 1.479819860511658591e-01;
    constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;
    constexpr long long kSqrtHalf = 0x3fe6a09e667f3bcdLL;  // bits of sqrt(2)/2
    const T u = 1.0 + x;
    // Shift the exponent field so that it gives k for m in [sqrt(2)/2, sqrt(2)).
    const auto hu = bits_of(u) + (0x3ff0000000000000LL - kSqrtHalf);
    // k as a double without an integer conversion: 2^52 + (k + 1023) has those bits.
    const T k = double_of(((hu >> 52) & 0x7ff) | 0x4330000000000000LL) - (4503599627370496.0 + 1023.0);
    const T m = double_of((hu & 0x000fffffffffffffLL) + kSqrtHalf);
    const auto reduced = k != 0.0;
    const T c = select(reduced, select(k >= 2.0, 1.0 - (u - x), x - (u - 1.0)) / u, T{});
    const T f = select(reduced, m - 1.0, x);
    const T hfsq = 0.5 * f * f;
    const T s = f / (2.0 + f);
    const T z = s * s, w = z * z;
    const T R = z * (kLg1 + w * (kLg3 + w * (kLg5 + w * kLg7))) + w * (kLg2 + w * (kLg4 + w * kLg6));
    return s * (hfsq + R) + (k * kLn2Lo + c) - hfsq + f + k * kLn2Hi;
}
inline double sqrt_lanes(double x) { return std::sqrt(x); }
inline Lanes sqrt_lanes(const Lanes& x) {
    Lanes r;
    for (int l = 0; l < kLanes; ++l) r[l] = std::sqrt(x[l]);
    return r;
}
// Cube root of the Jacobian J for the bulk-viscosity length. For 0.3 <= J <= 3 (any realistic
// element) four Halley steps y <- y (y^3 + 2J) / (2y^3 + J) from y = 1, in plain arithmetic that
// vectorizes (cubic convergence: measured against std::cbrt on 2e6 points of [0.3, 3], relative
// error <= 3.6e-14 after three steps, <= 7e-16 (3 ulp) after four); other J (and NaN) lane by lane
// with std::cbrt. The one-element and block kernels do the same operations: the same bits.
template <class T>
inline T halley_cbrt(const T& J) {
    T y = T{} + 1.0;
    for (int it = 0; it < 4; ++it) {
        const T y3 = y * y * y;
        y = y * (y3 + 2.0 * J) / (2.0 * y3 + J);
    }
    return y;
}
inline double cbrt_jacobian(double J) { return J >= 0.3 && J <= 3.0 ? halley_cbrt(J) : std::cbrt(J); }
inline Lanes cbrt_jacobian(const Lanes& J) {
    Lanes y = halley_cbrt(J);
    for (int l = 0; l < kLanes; ++l)
        if (!(J[l] >= 0.3 && J[l] <= 3.0)) y[l] = std::cbrt(J[l]);
    return y;
}

/// Table 2-1's solid step l / (Q + sqrt(Q^2 + c^2)), Q = C1 c + C0 l |tr D| in compression
/// (fem::cfl::solid_time_step lane by lane, the same operations).
template <class T>
[[gnu::always_inline]] inline T solid_time_step(const T& l, const T& trD, double c, const BulkViscosity& bulk) {
    const T Q = select(trD < 0.0, bulk.linear * c + bulk.quadratic * l * -trD, T{});  // -trD = |trD| there
    return l / (Q + sqrt_lanes(Q * Q + c * c));
}

/// The squared von Mises measure of a symmetric tensor given by its upper triangle s[i][j], j >= i.
template <class T>
[[gnu::always_inline]] inline T von_mises_sq(const T (&s)[3][3]) {
    const T d0 = s[0][0] - s[1][1], d1 = s[1][1] - s[2][2], d2 = s[2][2] - s[0][0];
    return 0.5 * (d0 * d0 + d1 * d1 + d2 * d2) + 3.0 * (s[0][1] * s[0][1] + s[1][2] * s[1][2] + s[0][2] * s[0][2]);
}

/// One material point of a solid element (what the kernels need of it).
template <class T>
struct MaterialPoint {
    T J;            // det F; <= 0: inverted (the other members are then meaningless)
    T ln_j;         // ln J
    T P[3][3];      // first Piola-Kirchhoff stress, viscous part included
    T Pv[3][3];     // its viscous part (set only when `viscous`)
    bool viscous;   // bulk viscosity or beta damping on: Pv set
    T W;            // stored energy per reference volume
    T b[3][3];      // F F^T - I (upper triangle): the elastic Cauchy stress is (mu b + lambda ln J I) / J
    T von_mises_sq; // of the elastic Cauchy stress
    T trD;          // tr D, the volumetric strain rate
    T power;        // sigma_visc : D (Cauchy viscous stress): the viscous power per current volume
};

/// The material point from the displacement gradient H = F - I and the deformation rate Fdot.
/// Compressible neo-Hookean: W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2, P = mu (F - F^-T) +
/// lambda ln J F^-T (element/hex8_explicit.hpp); viscous Cauchy stress from D = sym(Fdot F^-1): the
/// Table 2-1 bulk viscosity q = rho l (C0 l tr D^2 - C1 c tr D) in compression, with l = `length`
/// when > 0, else length0 cbrt(J) (the cube root of the current volume J V0 when length0 =
/// cbrt(V0)), and beta (2 mu D + lambda tr D I) (Eq 2-39).
template <class T>
[[gnu::always_inline]] inline void material_point(const hex8::Hex8Material& mat, const T (&H)[3][3],
                                                  const T (&Fd)[3][3], const T& length0, double length,
                                                  MaterialPoint<T>& out) {
    // J - 1 = det(I + H) - 1 = tr H + (tr^2 H - tr H^2)/2 + det H, without cancellation.
    const T trH = H[0][0] + H[1][1] + H[2][2];
    T trH2 = H[0][0] * H[0][0];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (i + j > 0) trH2 += H[i][j] * H[j][i];
    const T detH = H[0][0] * (H[1][1] * H[2][2] - H[1][2] * H[2][1]) - H[0][1] * (H[1][0] * H[2][2] - H[1][2] * H[2][0]) +
                   H[0][2] * (H[1][0] * H[2][1] - H[1][1] * H[2][0]);
    const T jm1 = trH + 0.5 * (trH * trH - trH2) + detH;
    const T J = 1.0 + jm1;
    out.J = J;
    T F[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) F[i][j] = i == j ? H[i][j] + 1.0 : H[i][j];
    // Cofactor matrix C of F: F^-T = C / J and J F^-T = C.
    T C[3][3];
    C[0][0] = F[1][1] * F[2][2] - F[1][2] * F[2][1];
    C[0][1] = F[1][2] * F[2][0] - F[1][0] * F[2][2];
    C[0][2] = F[1][0] * F[2][1] - F[1][1] * F[2][0];
    C[1][0] = F[0][2] * F[2][1] - F[0][1] * F[2][2];
    C[1][1] = F[0][0] * F[2][2] - F[0][2] * F[2][0];
    C[1][2] = F[0][1] * F[2][0] - F[0][0] * F[2][1];
    C[2][0] = F[0][1] * F[1][2] - F[0][2] * F[1][1];
    C[2][1] = F[0][2] * F[1][0] - F[0][0] * F[1][2];
    C[2][2] = F[0][0] * F[1][1] - F[0][1] * F[1][0];
    const T inv_j = 1.0 / J;
    const T lnJ = log1p_lanes(jm1);
    out.ln_j = lnJ;
    const double mu = mat.mu, lambda = mat.lambda;

    // Neo-Hookean first Piola-Kirchhoff stress P = mu (F - F^-T) + lambda ln J F^-T, stored energy.
    const T llj = lambda * lnJ;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const T finvt = C[i][j] * inv_j;
            out.P[i][j] = mu * (F[i][j] - finvt) + llj * finvt;
        }
    T h2 = H[0][0] * H[0][0];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (i + j > 0) h2 += H[i][j] * H[i][j];
    // W = mu/2 (I1 - 3 - 2 ln J) + lambda/2 ln^2 J with I1 - 3 = 2 tr H + |H|^2.
    out.W = 0.5 * mu * (2.0 * (trH - lnJ) + h2) + 0.5 * lambda * lnJ * lnJ;
    // Von Mises of the elastic Cauchy stress sigma = (mu (F F^T - I) + lambda ln J I) / J: only the
    // deviator of b = F F^T - I = H + H^T + H H^T counts, so vm = mu / J vm(b).
    for (int i = 0; i < 3; ++i)
        for (int j = i; j < 3; ++j)
            out.b[i][j] = H[i][j] + H[j][i] + H[i][0] * H[j][0] + H[i][1] * H[j][1] + H[i][2] * H[j][2];
    {
        const T sc = mu * inv_j;
        out.von_mises_sq = sc * sc * von_mises_sq(out.b);
    }

    // Viscous Cauchy stresses from the velocity gradient L = Fdot F^-1 = Fdot C^T / J.
    T L[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) L[i][j] = (Fd[i][0] * C[j][0] + Fd[i][1] * C[j][1] + Fd[i][2] * C[j][2]) * inv_j;
    const T trD = L[0][0] + L[1][1] + L[2][2];
    out.trD = trD;
    const bool beta_on = mat.rayleigh_beta > 0.0;
    out.viscous = mat.bulk_viscosity || beta_on;
    T power{};
    if (out.viscous) {
        T sv[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) sv[i][j] = T{};
        if (mat.bulk_viscosity) {
            // Table 2-1 / LS-DYNA bulk viscosity, in compression only: q = rho l (C0 l eps_kk^2 -
            // C1 c eps_kk), a pressure, with l the cube root of the current volume (LS-DYNA's choice
            // for solids) unless given.
            // Skipped when no lane compresses: q would be selected away in every lane (sv stays
            // +0, the same bits), and the cube root's four dependent divisions are the longest
            // chain of the point.
            const auto compressing = trD < 0.0;
            if (any(compressing)) {
                const T l = length > 0.0 ? T{} + length : length0 * cbrt_jacobian(J);
                const T rho = mat.density / J;
                // (wave_speed is set by Hex8Material::from; computed here for a hand-filled material)
                const double c = mat.wave_speed > 0.0 ? mat.wave_speed : std::sqrt((lambda + 2.0 * mu) / mat.density);
                const T q = rho * l * (mat.bulk.quadratic * l * trD * trD - mat.bulk.linear * c * trD);
                const T qc = select(compressing, q, T{});
                for (int i = 0; i < 3; ++i) sv[i][i] -= qc;
            }
        }
        if (beta_on) {
            // beta K v of Eq 2-39 as a viscous stress beta C : D (the tangent of the material at rest).
            const double b2mu = mat.rayleigh_beta * 2.0 * mu;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) sv[i][j] += b2mu * (0.5 * (L[i][j] + L[j][i]));
            for (int i = 0; i < 3; ++i) sv[i][i] += mat.rayleigh_beta * lambda * trD;
        }
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) power += sv[i][j] * (0.5 * (L[i][j] + L[j][i]));
        // P += J sv F^-T = sv C.
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                out.Pv[i][j] = sv[i][0] * C[0][j] + sv[i][1] * C[1][j] + sv[i][2] * C[2][j];
                out.P[i][j] += out.Pv[i][j];
            }
    }
    out.power = power;
}

}  // namespace fem::lanes
