#include "explicit/node_update.hpp"

#include <algorithm>
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

// Nodes per block of the two-pass update below (its buffers: ~10 kB on the stack, in L1).
constexpr int kBlock = 64;

}  // namespace

void update_node(const NodeUpdateData& d, int i, NodeSums& p) {
    const double dtavg = d.dtavg, dt_half = d.dt_half;
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
        return;
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
    const double alpha = d.alpha[i];
    const double a = alpha * dtavg * 0.5;
    const double s = dtavg / m;
    // (An undamped node, a = 0: (1 - 0) vm = vm and x / 1 = x exactly, the bits of vm + s F.)
    double vp[3];
    for (int k = 0; k < 3; ++k) vp[k] = ((1.0 - a) * vm[k] + s * F[k]) / (1.0 + a);
    const unsigned fx = d.fixed[i] & 7u;
    const int ti = d.target_index[i];
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
    const double vavg[3] = {0.5 * (vm[0] + vp[0]), 0.5 * (vm[1] + vp[1]), 0.5 * (vm[2] + vp[2])};
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

// Two passes per block of nodes. The first computes every node's new velocity and its terms of the
// energy sums as if the node were free, in loops without branches or loop-carried sums, which the
// compiler vectorizes (8 nodes per AVX-512 instruction: the three divisions by 1 + a of a damped
// node were the update's bottleneck as scalar vdivsd). The second adds the terms to the sums node
// by node, in node order, and writes v and x; a constrained node (update_node) is done
// there whole, in its place in that order. Each term is the same IEEE operations in the same order
// as the scalar update's (fp-contract=off; an undamped node's (1 - 0) vm / (1 + 0) is vm exactly),
// and each sum receives the same terms in the same order: the same bits.
FEM_NODE_UPDATE_CLONES
NodeSums update_nodes(const NodeUpdateData& d, int i0, int i1) {
    static_assert(sizeof(Vec3) == 3 * sizeof(double), "nodal vectors are 3 contiguous doubles");
    NodeSums p;
    const double dtavg = d.dtavg, dt_half = d.dt_half;
    const double* v = d.v[0].data();
    const double* f = d.f[0].data();
    const double* fe = d.fext[0].data();
    const double* fp = d.providers ? d.fprov[0].data() : nullptr;
    const double* fv = d.book_viscous ? d.fv[0].data() : nullptr;
    alignas(64) double F[3][kBlock], vp[3][kBlock], ke[kBlock], kp[kBlock], we[kBlock], wh[kBlock], dm[kBlock], dh[kBlock];
    alignas(64) double pw[kBlock], ph[kBlock], vw[kBlock], vh[kBlock];
    for (int b = i0; b < i1; b += kBlock) {
        const int n = std::min(kBlock, i1 - b);
        // Pass 1: every node of the block as a free node (a massless node gives inf or NaN here,
        // unused). Separate loops without branches, which the vectorizer takes.
        if (fp)
            for (int l = 0; l < n; ++l)
                for (int k = 0; k < 3; ++k) F[k][l] = fe[3 * (b + l) + k] + fp[3 * (b + l) + k] - f[3 * (b + l) + k];
        else
            for (int l = 0; l < n; ++l)
                for (int k = 0; k < 3; ++k) F[k][l] = fe[3 * (b + l) + k] - f[3 * (b + l) + k];
        for (int l = 0; l < n; ++l) {
            const int i = b + l;
            const double m = d.mass[i], alpha = d.alpha[i];
            const double a = alpha * dtavg * 0.5;
            const double s = dtavg / m;
            const double vm[3] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
            double w[3];
            for (int k = 0; k < 3; ++k) {
                w[k] = ((1.0 - a) * vm[k] + s * F[k][l]) / (1.0 + a);
                vp[k][l] = w[k];
            }
            const double vavg[3] = {0.5 * (vm[0] + w[0]), 0.5 * (vm[1] + w[1]), 0.5 * (vm[2] + w[2])};
            const double fei[3] = {fe[3 * i], fe[3 * i + 1], fe[3 * i + 2]};
            we[l] = dot(fei, vavg) * dtavg;
            wh[l] = 0.5 * dot(fei, vm) * dtavg;
            dm[l] = alpha != 0.0 ? alpha * m * dot(vavg, vavg) * dtavg : 0.0;
            dh[l] = alpha != 0.0 ? 0.5 * alpha * m * dot(vavg, vm) * dtavg : 0.0;
            ke[l] = 0.5 * m * dot(vm, w);
            kp[l] = 0.5 * m * dot(w, w);
        }
        if (fp)
            for (int l = 0; l < n; ++l) {
                const int i = b + l;
                const double vm[3] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
                const double vavg[3] = {0.5 * (vm[0] + vp[0][l]), 0.5 * (vm[1] + vp[1][l]), 0.5 * (vm[2] + vp[2][l])};
                const double fpi[3] = {fp[3 * i], fp[3 * i + 1], fp[3 * i + 2]};
                const bool touched = fpi[0] != 0.0 || fpi[1] != 0.0 || fpi[2] != 0.0;
                pw[l] = touched ? dot(fpi, vavg) * dtavg : 0.0;
                ph[l] = touched ? 0.5 * dot(fpi, vm) * dtavg : 0.0;
            }
        if (fv)
            for (int l = 0; l < n; ++l) {
                const int i = b + l;
                const double vm[3] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
                const double vavg[3] = {0.5 * (vm[0] + vp[0][l]), 0.5 * (vm[1] + vp[1][l]), 0.5 * (vm[2] + vp[2][l])};
                const double fvi[3] = {fv[3 * i], fv[3 * i + 1], fv[3 * i + 2]};
                vw[l] = dot(fvi, vavg) * dtavg;
                vh[l] = 0.5 * dot(fvi, vm) * dtavg;
            }
        // Pass 2: the sums in node order, v and x. The terms the scalar update skipped (no mass
        // damping on the node, no contact force on it) are +0 here: adding +0 leaves these sums'
        // bits as they are (they start at +0 and never become -0), without a branch per node.
        for (int l = 0; l < n; ++l) {
            const int i = b + l;
            if (!(d.mass[i] > 0.0) || (d.fixed[i] & 7u) || d.target_index[i] >= 0) {
                update_node(d, i, p);
                continue;
            }
            if (d.loads) {
                p.wext += we[l];
                p.wext_half += wh[l];
                p.wabs += std::abs(we[l]);
            }
            p.damp += dm[l];
            p.damp_half += dh[l];
            if (fp) {
                p.wprov += pw[l];
                p.wprov_half += ph[l];
            }
            if (fv) {
                p.visc += vw[l];
                p.visc_half += vh[l];
            }
            p.ke += ke[l];
            p.ke_plus += kp[l];
            if (!std::isfinite(kp[l]) && p.bad < 0) p.bad = i;
            double* vi = d.v[i].data();
            double* xi = d.x[i].data();
            for (int k = 0; k < 3; ++k) {
                vi[k] = vp[k][l];
                xi[k] += dt_half * vp[k][l];
            }
        }
    }
    return p;
}

}  // namespace fem::explicit_detail
