#include "explicit/node_update.hpp"

#include <cmath>

// No a * b + c contracted into an FMA (the AVX-512 and AVX2 versions below have FMA, the baseline
// has not): every version gives the bits of the baseline x86-64 code.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("fp-contract=off")
#endif

// As the element kernels (element/kernel_lanes.hpp): GCC only, on x86-64 without -march=native.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__AVX512F__)
#define FEM_NODE_UPDATE_CLONES [[gnu::target_clones("avx512f", "avx2", "default")]]
#else
#define FEM_NODE_UPDATE_CLONES
#endif

namespace fem::explicit_detail {

namespace {
// Eigen's Vec3 dot product, ((a0 b0 + a1 b1) + a2 b2), in plain arithmetic.
inline double dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
}  // namespace

FEM_NODE_UPDATE_CLONES
NodeSums update_nodes(const NodeUpdateData& d, int i0, int i1) {
    static_assert(sizeof(Vec3) == 3 * sizeof(double), "nodal vectors are 3 contiguous doubles");
    NodeSums p;
    const double dtavg = d.dtavg, dt_half = d.dt_half;
    for (int i = i0; i < i1; ++i) {
        double* v = d.v[i].data();
        double* x = d.x[i].data();
        const double m = d.mass[i];
        if (!(m > 0.0)) {  // a node no element uses: it moves only when prescribed (rigid parts)
            const int ti = d.target_index[i];
            if (ti >= 0) {
                double vp[3] = {0.0, 0.0, 0.0};
                for (int k = 0; k < 3; ++k)
                    if (!((d.fixed[i] >> k) & 1u) && !std::isnan(d.target[ti][k])) vp[k] = d.target[ti][k];
                for (int k = 0; k < 3; ++k) {
                    v[k] = vp[k];
                    x[k] += dt_half * vp[k];
                }
            }
            continue;
        }
        const double vm[3] = {v[0], v[1], v[2]};
        const double* fi = d.f[i].data();
        const double* fe = d.fext[i].data();
        double F[3];
        if (d.providers) {
            const double* fp = d.fprov[i].data();
            for (int k = 0; k < 3; ++k) F[k] = fe[k] + fp[k] - fi[k];
        } else {
            for (int k = 0; k < 3; ++k) F[k] = fe[k] - fi[k];
        }
        // Undamped nodes (a = 0) skip the three divisions by 1 + a = 1: (1 - 0) vm = vm and
        // x / 1 = x exactly, so the same bits.
        const double alpha = d.alpha[i];
        const double a = alpha * dtavg * 0.5;
        const double s = dtavg / m;
        double vp[3];
        if (a == 0.0)
            for (int k = 0; k < 3; ++k) vp[k] = vm[k] + s * F[k];
        else
            for (int k = 0; k < 3; ++k) vp[k] = ((1.0 - a) * vm[k] + s * F[k]) / (1.0 + a);
        const unsigned fx = d.fixed[i] & 7u;
        const int ti = d.target_index[i];
        if (fx || ti >= 0) {
            for (int k = 0; k < 3; ++k) {
                if ((fx >> k) & 1u)
                    vp[k] = 0.0;
                else if (ti >= 0 && !std::isnan(d.target[ti][k]))
                    vp[k] = d.target[ti][k];
                else
                    continue;
                // Work of the reaction that enforces the constraint.
                const double va = 0.5 * (vm[k] + vp[k]);
                const double R = m * (vp[k] - vm[k]) / dtavg - F[k] + alpha * m * va;
                p.wext += R * dtavg * va;
                p.wext_half += 0.5 * R * dtavg * vm[k];
                p.wabs += std::abs(R * dtavg * va);
            }
        }
        const double vavg[3] = {0.5 * (vm[0] + vp[0]), 0.5 * (vm[1] + vp[1]), 0.5 * (vm[2] + vp[2])};
        // Terms that are zero are skipped (no loads: fext = 0; no mass damping: alpha = 0; no
        // contact force on the node): adding a zero leaves these sums' bits as they are (they start
        // at +0 and never become -0).
        if (d.loads) {
            const double we = dot(fe, vavg) * dtavg;
            p.wext += we;
            p.wext_half += 0.5 * dot(fe, vm) * dtavg;
            p.wabs += std::abs(we);
        }
        if (alpha != 0.0) {
            p.damp += alpha * m * dot(vavg, vavg) * dtavg;
            p.damp_half += 0.5 * alpha * m * dot(vavg, vm) * dtavg;
        }
        if (d.providers) {
            const double* fp = d.fprov[i].data();
            if (fp[0] != 0.0 || fp[1] != 0.0 || fp[2] != 0.0) {
                p.wprov += dot(fp, vavg) * dtavg;
                p.wprov_half += 0.5 * dot(fp, vm) * dtavg;
            }
        }
        if (d.book_viscous) {
            const double* fv = d.fv[i].data();
            p.visc += dot(fv, vavg) * dtavg;
            p.visc_half += 0.5 * dot(fv, vm) * dtavg;
        }
        p.ke += 0.5 * m * dot(vm, vp);
        const double kp = 0.5 * m * dot(vp, vp);
        p.ke_plus += kp;
        if (!std::isfinite(kp) && p.bad < 0) p.bad = i;
        for (int k = 0; k < 3; ++k) {
            v[k] = vp[k];
            x[k] += dt_half * vp[k];
        }
    }
    return p;
}

}  // namespace fem::explicit_detail
