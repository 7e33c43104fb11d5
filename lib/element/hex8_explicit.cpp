#include "element/hex8_explicit.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"
// The lane helpers and the material point shared with the tetrahedra; it also sets fp-contract=off
// for this whole file (no FMA: every version of the kernel gives the same bits, hex8_explicit.hpp).
#include "element/kernel_lanes.hpp"
#include "element/lane_gather.hpp"

namespace fem::hex8 {
namespace {
// Natural coordinates of the nodes (node order of mesh/element_shape.hpp).
constexpr double kS[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                             {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
}  // namespace

Hex8Reference make_reference(const std::array<Vec3, 8>& X, const char* element_name) {
    Hex8Reference r;
    for (auto& b : r.B) b.setZero();
    const double g = 1.0 / std::sqrt(3.0);
    // B_a = integral dN_a/dX dV = sum_q J^{-T} dN_a/dxi det J = sum_q adj(J)^T dN_a/dxi: exact with 2x2x2
    // Gauss (the integrand is at most quadratic in each natural coordinate).
    double min_det = 1e300;
    for (int q = 0; q < 8; ++q) {
        const double xi = kS[q][0] * g, eta = kS[q][1] * g, zeta = kS[q][2] * g;
        std::array<Vec3, 8> dN;
        Mat3 J = Mat3::Zero();  // J(i, k) = dx_i / dxi_k
        for (int a = 0; a < 8; ++a) {
            dN[a] = Vec3(0.125 * kS[a][0] * (1 + kS[a][1] * eta) * (1 + kS[a][2] * zeta),
                         0.125 * kS[a][1] * (1 + kS[a][0] * xi) * (1 + kS[a][2] * zeta),
                         0.125 * kS[a][2] * (1 + kS[a][0] * xi) * (1 + kS[a][1] * eta));
            J += X[a] * dN[a].transpose();
        }
        const double det = J.determinant();
        min_det = std::min(min_det, det);
        r.volume += det;
        // dN/dX = J^{-T} dN/dxi, so dN/dX det J = (det J J^{-1})^T dN/dxi = adj(J)^T dN/dxi.
        const Mat3 adjT = (det * J.inverse()).transpose();
        for (int a = 0; a < 8; ++a) r.B[a] += adjT * dN[a];
    }
    if (!(min_det > 0.0) || !(r.volume > 0.0))
        throw InputError(fmt::format("{}: inverted or degenerate hexahedron (det J = {:.3g} at a Gauss point, "
                                     "volume {:.3g}); check the node order (bottom face counter-clockwise "
                                     "seen from the top, then the top face)",
                                     element_name, min_det, r.volume));
    // Hourglass base vectors h = xi eta, eta zeta, zeta xi, xi eta zeta at the nodes, made orthogonal
    // to linear fields (Flanagan-Belytschko 1981, Eq 56): gamma = h - (h . X_b) B / V0.
    for (int al = 0; al < 4; ++al) {
        std::array<double, 8> h;
        for (int a = 0; a < 8; ++a) {
            const double x = kS[a][0], y = kS[a][1], z = kS[a][2];
            h[a] = al == 0 ? x * y : al == 1 ? y * z : al == 2 ? z * x : x * y * z;
        }
        Vec3 hx = Vec3::Zero();
        for (int a = 0; a < 8; ++a) hx += h[a] * X[a];
        r.hourglass_base[al] = hx;
        for (int a = 0; a < 8; ++a) r.gamma[al][a] = h[a] - hx.dot(r.B[a]) / r.volume;
    }
    double s = 0.0;
    for (const auto& b : r.B) s += b.squaredNorm();
    r.hourglass_norm = s / r.volume;
    return r;
}

Hex8Material Hex8Material::from(const ElasticMaterial& m, double qm, double beta, BulkViscosity q,
                                bool bulk_on) {
    Hex8Material h;
    h.mu = m.shear_modulus();
    h.lambda = m.lame_lambda();
    h.density = m.density;
    h.hourglass_qm = qm;
    h.rayleigh_beta = beta;
    h.bulk = q;
    h.bulk_viscosity = bulk_on;
    h.wave_speed = std::sqrt((h.lambda + 2.0 * h.mu) / h.density);
    return h;
}

double von_mises(const Mat3& s) {
    const double a = s(0, 0) - s(1, 1), b = s(1, 1) - s(2, 2), c = s(2, 2) - s(0, 0);
    return std::sqrt(0.5 * (a * a + b * b + c * c) +
                     3.0 * (s(0, 1) * s(0, 1) + s(1, 2) * s(1, 2) + s(0, 2) * s(0, 2)));
}

void internal_force(const Hex8Reference& ref, const Hex8Material& mat, const std::array<Vec3, 8>& u,
                    const std::array<Vec3, 8>& v, double length, Hex8Result& out) {
    double ua[3][8], va[3][8];
    for (int a = 0; a < 8; ++a)
        for (int i = 0; i < 3; ++i) {
            ua[i][a] = u[a][i];
            va[i][a] = v[a][i];
        }
    Hex8KernelResult r;
    internal_force(pack(ref, mat), mat, ua, va, length, r);
    out.jacobian = r.jacobian;
    out.inverted = !(r.jacobian > 0.0);
    if (out.inverted) return;
    for (int a = 0; a < 8; ++a) out.force[a] = Vec3(r.f[0][a], r.f[1][a], r.f[2][a]);
    out.strain_energy = r.strain_energy;
    out.hourglass_energy = r.hourglass_energy;
    out.viscous_power = r.viscous_power;
    out.volumetric_strain_rate = r.volumetric_strain_rate;
    out.von_mises = std::sqrt(r.von_mises_sq);
    // Elastic Cauchy stress sigma = P F^T / J = (mu (F F^T - I) + lambda ln J I) / J, with
    // F F^T - I = H + H^T + H H^T (no cancellation at small strain).
    Mat3 H;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) H(i, j) = r.H[i][j];
    const Mat3 b = H + H.transpose() + H * H.transpose();
    out.cauchy = (mat.mu * b + mat.lambda * r.ln_j * Mat3::Identity()) / r.jacobian;
}

// --- the per-cycle kernel -------------------------------------------------------------------------

namespace {
// h_alpha at the nodes: xi eta, eta zeta, zeta xi, xi eta zeta (entries +-1).
constexpr std::array<std::array<double, 8>, 4> hourglass_vectors() {
    std::array<std::array<double, 8>, 4> h{};
    for (int a = 0; a < 8; ++a) {
        h[0][a] = kS[a][0] * kS[a][1];
        h[1][a] = kS[a][1] * kS[a][2];
        h[2][a] = kS[a][2] * kS[a][0];
        h[3][a] = kS[a][0] * kS[a][1] * kS[a][2];
    }
    return h;
}
constexpr auto kH = hourglass_vectors();
}  // namespace

Hex8Packed pack(const Hex8Reference& ref, const Hex8Material& mat) {
    Hex8Packed p;
    for (int a = 0; a < 8; ++a)
        for (int i = 0; i < 3; ++i) p.B[i][a] = ref.B[a][i];
    for (int al = 0; al < 4; ++al)
        for (int i = 0; i < 3; ++i) p.hx[al][i] = ref.hourglass_base[al][i];
    p.volume = ref.volume;
    p.hourglass_k = mat.hourglass_qm * 2.0 * mat.mu * ref.hourglass_norm / 8.0;
    p.length0 = std::cbrt(ref.volume);
    return p;
}

void pack_lane(const Hex8Packed& p, int l, Hex8PackedBlock& b) {
    for (int i = 0; i < 3; ++i)
        for (int a = 0; a < 8; ++a) b.B[i][a][l] = p.B[i][a];
    for (int al = 0; al < 4; ++al)
        for (int i = 0; i < 3; ++i) b.hx[al][i][l] = p.hx[al][i];
    b.volume[l] = p.volume;
    b.hourglass_k[l] = p.hourglass_k;
    b.length0[l] = p.length0;
}

namespace {
using lanes::select;
using lanes::sqrt_lanes;

template <class T>
[[gnu::always_inline]] inline void kernel(const Hex8PackedT<T>& p, const Hex8Material& mat, const T (&u)[3][8], const T (&v)[3][8], double length,
            Hex8KernelResultT<T>& out, bool viscous_forces) {
    // Displacement gradient H = F - I from the displacements (not the positions): the strain, the
    // stored energy and the hourglass displacements keep full precision at small strain and far
    // from the origin. Fdot likewise from the velocities.
    const T inv_v0 = 1.0 / p.volume;
    T H[3][3], Fd[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            T h = u[i][0] * p.B[j][0], fd = v[i][0] * p.B[j][0];
            for (int a = 1; a < 8; ++a) {
                h += u[i][a] * p.B[j][a];
                fd += v[i][a] * p.B[j][a];
            }
            H[i][j] = h * inv_v0;
            Fd[i][j] = fd * inv_v0;
            out.H[i][j] = H[i][j];
        }
    // The material point (stress, energy, viscous stresses), shared with the tetrahedra.
    lanes::MaterialPoint<T> m;
    lanes::material_point(mat, H, Fd, p.length0, length, m);
    out.jacobian = m.J;  // J <= 0: inverted; the caller discards the rest (NaNs are harmless)
    out.ln_j = m.ln_j;
    out.strain_energy = p.volume * m.W;
    out.von_mises_sq = m.von_mises_sq;
    out.volumetric_strain_rate = m.trD;
    T P[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) P[i][j] = m.P[i][j];
    // The viscous forces alone, for the solver's exact booking of viscous work (NodalState::fv).
    if (viscous_forces) {
        for (int i = 0; i < 3; ++i)
            for (int a = 0; a < 8; ++a)
                out.fv[i][a] = m.viscous ? m.Pv[i][0] * p.B[0][a] + m.Pv[i][1] * p.B[1][a] + m.Pv[i][2] * p.B[2][a] : T{};
    }
    out.viscous_power = m.J * p.volume * m.power;

    // Flanagan-Belytschko stiffness hourglass control, folded (see the header): kq_alpha = k q_alpha
    // with q_alpha = sum_a h_alpha,a u_a - H hX_alpha; P -= (1/V0) sum_alpha kq_alpha (x) hX_alpha.
    const T k = p.hourglass_k;
    T kq[4][3];
    T e_hg{};
    for (int al = 0; al < 4; ++al)
        for (int i = 0; i < 3; ++i) {
            T sum = kH[al][0] > 0 ? u[i][0] : -u[i][0];
            for (int a = 1; a < 8; ++a) sum = kH[al][a] > 0 ? sum + u[i][a] : sum - u[i][a];
            const T q = sum - (H[i][0] * p.hx[al][0] + H[i][1] * p.hx[al][1] + H[i][2] * p.hx[al][2]);
            e_hg += q * q;
            kq[al][i] = k * q;
        }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            P[i][j] -= inv_v0 * (kq[0][i] * p.hx[0][j] + kq[1][i] * p.hx[1][j] + kq[2][i] * p.hx[2][j] +
                                 kq[3][i] * p.hx[3][j]);
    out.hourglass_energy = 0.5 * k * e_hg;
    for (int i = 0; i < 3; ++i)
        for (int a = 0; a < 8; ++a) {
            T g = kH[0][a] > 0 ? kq[0][i] : -kq[0][i];
            for (int al = 1; al < 4; ++al) g = kH[al][a] > 0 ? g + kq[al][i] : g - kq[al][i];
            out.f[i][a] = P[i][0] * p.B[0][a] + P[i][1] * p.B[1][a] + P[i][2] * p.B[2][a] + g;
        }
}

template <class T>
[[gnu::always_inline]] inline T volume_of(const T (&x)[3][8]) {
    // x(xi) = c0 + c1 xi + c2 eta + c3 zeta + c4 xi eta + c5 eta zeta + c6 zeta xi + c7 xi eta zeta
    // with c_k = (1/8) sum_a s_k,a x_a. det J = [x_xi, x_eta, x_zeta] (triple product) averaged over
    // the natural cube (volume 8, <xi^2> = 1/3, odd moments 0): only the products whose monomials are
    // even in every coordinate survive, and those with a repeated vector vanish, leaving
    //   V = 8 ([c1,c2,c3] + ([c1,c4,c6] + [c4,c2,c5] + [c6,c5,c3]) / 3).
    // With d_k = 8 c_k: V = ([d1,d2,d3] + ([d1,d4,d6] + [d4,d2,d5] + [d6,d5,d3]) / 3) / 64.
    T d[7][3];
    for (int i = 0; i < 3; ++i) {
        const T* c = x[i];
        d[1][i] = (c[1] - c[0]) + (c[2] - c[3]) + (c[5] - c[4]) + (c[6] - c[7]);  // s_xi
        d[2][i] = (c[2] - c[1]) + (c[3] - c[0]) + (c[6] - c[5]) + (c[7] - c[4]);  // s_eta
        d[3][i] = (c[4] - c[0]) + (c[5] - c[1]) + (c[6] - c[2]) + (c[7] - c[3]);  // s_zeta
        d[4][i] = (c[0] - c[1]) + (c[2] - c[3]) + (c[4] - c[5]) + (c[6] - c[7]);  // s_xi s_eta
        d[5][i] = (c[0] - c[4]) + (c[1] - c[5]) + (c[6] - c[2]) + (c[7] - c[3]);  // s_eta s_zeta
        d[6][i] = (c[0] - c[4]) + (c[6] - c[2]) + (c[5] - c[1]) + (c[3] - c[7]);  // s_zeta s_xi
    }
    auto triple = [&](int a, int b, int c) {
        return d[a][0] * (d[b][1] * d[c][2] - d[b][2] * d[c][1]) + d[a][1] * (d[b][2] * d[c][0] - d[b][0] * d[c][2]) +
               d[a][2] * (d[b][0] * d[c][1] - d[b][1] * d[c][0]);
    };
    return (triple(1, 2, 3) + (triple(1, 4, 6) + triple(4, 2, 5) + triple(6, 5, 3)) / 3.0) / 64.0;
}

template <class T>
[[gnu::always_inline]] inline T length_of(const T (&x)[3][8]) {
    // Faces as fem::cfl::hexahedron_length: (a, b, c, d) -> area |(c - a) x (d - b)| / 2. The
    // largest area comes from the largest squared norm: one square root.
    static constexpr int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                        {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    T largest{};
    for (const auto& f : faces) {
        T p[3], q[3];
        for (int i = 0; i < 3; ++i) {
            p[i] = x[i][f[2]] - x[i][f[0]];
            q[i] = x[i][f[3]] - x[i][f[1]];
        }
        const T n0 = p[1] * q[2] - p[2] * q[1], n1 = p[2] * q[0] - p[0] * q[2], n2 = p[0] * q[1] - p[1] * q[0];
        const T n = n0 * n0 + n1 * n1 + n2 * n2;
        largest = select(n > largest, n, largest);
    }
    return volume_of(x) / (0.5 * sqrt_lanes(largest));
}
}  // namespace

void internal_force(const Hex8Packed& p, const Hex8Material& mat, const double (&u)[3][8], const double (&v)[3][8],
                    double length, Hex8KernelResult& out, bool viscous_forces) {
    kernel(p, mat, u, v, length, out, viscous_forces);
}

// The block functions are compiled for AVX-512, AVX2 and baseline x86-64 (kernel_lanes.hpp).
#define FEM_HEX8_CLONES FEM_KERNEL_CLONES

FEM_HEX8_CLONES
void internal_force(const Hex8PackedBlock& p, const Hex8Material& mat, const Lanes (&u)[3][8], const Lanes (&v)[3][8],
                    Hex8KernelResultBlock& out, bool viscous_forces) {
    kernel(p, mat, u, v, 0.0, out, viscous_forces);
}

double kernel_log1p(double x) { return lanes::log1p_lanes(x); }

double exact_volume(const double (&x)[3][8]) { return volume_of(x); }
double characteristic_length(const double (&x)[3][8]) { return length_of(x); }
FEM_HEX8_CLONES
void characteristic_length(const Lanes (&x)[3][8], Lanes& length) { length = length_of(x); }

FEM_HEX8_CLONES
void critical_time_step(const Lanes (&x)[3][8], const Lanes& trD, double c, const BulkViscosity& bulk, Lanes& dt) {
    dt = lanes::solid_time_step(length_of(x), trD, c, bulk);
}

void gather(const double* xs, const double* Xs, const double* vs, const std::array<int, 8>* conn, int lanes,
            Lanes (&x)[3][8], Lanes (&u)[3][8], Lanes (&v)[3][8]) {
    gather_lanes<8, 8>(xs, Xs, vs, conn, lanes, x, u, v);  // element/lane_gather.hpp
}

namespace {
void to_arrays(const std::array<Vec3, 8>& x, double (&xa)[3][8]) {
    for (int a = 0; a < 8; ++a)
        for (int i = 0; i < 3; ++i) xa[i][a] = x[a][i];
}
}  // namespace

double exact_volume(const std::array<Vec3, 8>& x) {
    double xa[3][8];
    to_arrays(x, xa);
    return exact_volume(xa);
}

double characteristic_length(const std::array<Vec3, 8>& x) {
    double xa[3][8];
    to_arrays(x, xa);
    return characteristic_length(xa);
}

}  // namespace fem::hex8
