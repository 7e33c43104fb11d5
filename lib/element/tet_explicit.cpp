#include "element/tet_explicit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "core/eigen_instances.hpp"
#include "core/error.hpp"
#include "element/solid_elements.hpp"
// The lane helpers and the material point shared with the hexahedron; it also sets fp-contract=off
// for this whole file (no FMA: every version of the kernel gives the same bits).
#include "element/kernel_lanes.hpp"
#include "element/lane_gather.hpp"

namespace fem::tet {

namespace {

// Natural coordinates: xi = L1, eta = L2, zeta = L3, L0 = 1 - xi - eta - zeta; reference volume 1/6.
// Derivatives of the shape functions with respect to (xi, eta, zeta) at a point.
void shape_derivatives(const Vec3& p, std::array<Vec3, 4>& d) {
    (void)p;
    d[0] = Vec3(-1, -1, -1);
    d[1] = Vec3(1, 0, 0);
    d[2] = Vec3(0, 1, 0);
    d[3] = Vec3(0, 0, 1);
}

// Tet10 (Gmsh order): corners N_i = L_i (2 L_i - 1), mid-edge node of edge (i, j) N = 4 L_i L_j.
constexpr int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}};

void shape_derivatives(const Vec3& p, std::array<Vec3, 10>& d) {
    const double L[4] = {1.0 - p.x() - p.y() - p.z(), p.x(), p.y(), p.z()};
    const Vec3 dL[4] = {Vec3(-1, -1, -1), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    for (int i = 0; i < 4; ++i) d[i] = (4.0 * L[i] - 1.0) * dL[i];
    for (int k = 0; k < 6; ++k) {
        const int i = kEdge[k][0], j = kEdge[k][1];
        d[4 + k] = 4.0 * (L[i] * dL[j] + L[j] * dL[i]);
    }
}

template <int N, int Q>
Reference<N, Q> make_reference(std::span<const Vec3> X, const std::array<Vec3, Q>& points, double w,
                               const char* element_name) {
    if (static_cast<int>(X.size()) != N)
        throw InputError(fmt::format("{}: {} nodes given, {} expected", element_name, X.size(), N));
    Reference<N, Q> ref;
    for (int q = 0; q < Q; ++q) {
        std::array<Vec3, N> d;
        shape_derivatives(points[q], d);
        Mat3 J = Mat3::Zero();  // J_ij = dX_i / dxi_j
        for (int a = 0; a < N; ++a) J += X[a] * d[a].transpose();
        const double det = J.determinant();
        if (!(det > 0.0) || !std::isfinite(det))
            throw InputError(fmt::format("{}: non-positive Jacobian {:.4g} at integration point {} (inverted or "
                                         "degenerate element)",
                                         element_name, det, q));
        ref.jinv[q] = J.inverse();
        const Mat3 jinvt = ref.jinv[q].transpose();
        for (int a = 0; a < N; ++a) ref.dndx[q][a] = jinvt * d[a];
        ref.weight[q] = w * det;
        ref.volume += ref.weight[q];
    }
    return ref;
}

}  // namespace

Tet4Reference make_tet4_reference(std::span<const Vec3> X, const char* element_name) {
    // One point at the centroid, weight = reference volume 1/6 (N linear: exact).
    return make_reference<4, 1>(X, {Vec3(0.25, 0.25, 0.25)}, 1.0 / 6.0, element_name);
}

// The 4-point rule of degree 2 of the tet10: barycentric (a, b, b, b) and permutations, weights
// 1/24 (of the natural volume 1/6). Point q has L_q = a and the other three b.
constexpr double kRuleA = 0.5854101966249685, kRuleB = 0.1381966011250105;

Tet10Reference make_tet10_reference(std::span<const Vec3> X, const char* element_name) {
    const double a = kRuleA, b = kRuleB;  // (xi, eta, zeta) = (L1, L2, L3)
    return make_reference<10, 4>(X, {Vec3(b, b, b), Vec3(a, b, b), Vec3(b, a, b), Vec3(b, b, a)}, 1.0 / 24.0,
                                 element_name);
}

template <int N, int Q>
void internal_force(const Reference<N, Q>& ref, const hex8::Hex8Material& mat, std::span<const Vec3> x,
                    std::span<const Vec3> v, Result<N>& out) {
    const double mu = mat.mu, lambda = mat.lambda;
    for (auto& f : out.force) f.setZero();
    for (auto& f : out.viscous_force) f.setZero();
    out.strain_energy = out.viscous_power = out.volumetric_strain_rate = 0.0;
    out.min_jacobian = std::numeric_limits<double>::infinity();
    out.cauchy.setZero();
    double current_volume = 0.0;
    for (int q = 0; q < Q; ++q) {
        const auto& g = ref.dndx[q];
        Mat3 F = Mat3::Zero(), Fd = Mat3::Zero();
        for (int a = 0; a < N; ++a) {
            F.noalias() += x[a] * g[a].transpose();
            Fd.noalias() += v[a] * g[a].transpose();
        }
        const double J = F.determinant();
        out.min_jacobian = std::min(out.min_jacobian, J);
        if (!(J > 0.0) || !std::isfinite(J)) {
            for (auto& f : out.force) f.setZero();
            out.min_jacobian = std::isfinite(J) ? std::min(J, 0.0) : -1.0;
            return;
        }
        const Mat3 finvt = F.inverse().transpose();
        const double lnJ = std::log(J);
        const double w = ref.weight[q];
        // P = mu (F - F^-T) + lambda ln J F^-T; W = mu/2 (I1 - 3 - 2 ln J) + lambda/2 ln^2 J.
        Mat3 P = mu * (F - finvt) + lambda * lnJ * finvt;
        out.strain_energy += w * (0.5 * mu * (F.squaredNorm() - 3.0 - 2.0 * lnJ) + 0.5 * lambda * lnJ * lnJ);
        const Mat3 b = F * F.transpose();
        out.cauchy += w * (mu * (b - Mat3::Identity()) + lambda * lnJ * Mat3::Identity());  // J sigma w
        current_volume += w * J;
        // Viscous Cauchy stresses from L = Fdot F^-1 (as the hexahedron).
        const Mat3 L = Fd * finvt.transpose();
        const Mat3 D = 0.5 * (L + L.transpose());
        const double trD = D.trace();
        out.volumetric_strain_rate += w * J * trD;
        if (mat.bulk_viscosity || mat.rayleigh_beta > 0.0) {
            Mat3 sv = Mat3::Zero();
            if (mat.bulk_viscosity && trD < 0.0) {
                // Table 2-1 bulk viscosity pressure q = rho l (C0 l eps_kk^2 - C1 c eps_kk), l = cube
                // root of the current element volume.
                const double l = std::cbrt(J * ref.volume);
                const double rho = mat.density / J;
                const double qv = rho * l * (mat.bulk.quadratic * l * trD * trD - mat.bulk.linear * mat.wave_speed * trD);
                sv.diagonal().array() -= qv;
            }
            if (mat.rayleigh_beta > 0.0) sv += mat.rayleigh_beta * (2.0 * mu * D + lambda * trD * Mat3::Identity());
            out.viscous_power += w * J * (sv.cwiseProduct(D)).sum();
            const Mat3 Pv = J * sv * finvt;  // first Piola-Kirchhoff of the viscous Cauchy stress
            P += Pv;
            for (int a = 0; a < N; ++a) out.viscous_force[a].noalias() += w * (Pv * g[a]);
        }
        for (int a = 0; a < N; ++a) out.force[a].noalias() += w * (P * g[a]);
    }
    out.cauchy /= current_volume;
    out.volumetric_strain_rate /= current_volume;
    out.von_mises = hex8::von_mises(out.cauchy);
}

template <int N, int Q>
Eigen::MatrixXd linear_stiffness(const Reference<N, Q>& ref, const hex8::Hex8Material& mat) {
    // d f_a,i / d u_b,j at F = I: lambda g_a,i g_b,j + mu g_a,j g_b,i + mu delta_ij g_a . g_b.
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * N, 3 * N);
    for (int q = 0; q < Q; ++q) {
        const auto& g = ref.dndx[q];
        const double w = ref.weight[q];
        for (int a = 0; a < N; ++a)
            for (int b = 0; b < N; ++b) {
                const Mat3 k = mat.lambda * g[a] * g[b].transpose() + mat.mu * g[b] * g[a].transpose() +
                               mat.mu * g[a].dot(g[b]) * Mat3::Identity();
                K.block<3, 3>(3 * a, 3 * b) += w * k;
            }
    }
    return K;
}

std::array<double, 4> tet4_lumped_mass(std::span<const Vec3> X, double density) {
    const double V = std::abs((X[1] - X[0]).dot((X[2] - X[0]).cross(X[3] - X[0]))) / 6.0;
    const double m = density * V / 4.0;
    return {m, m, m, m};
}

std::array<double, 10> tet10_lumped_mass(std::span<const Vec3> X, double density) {
    const Eigen::MatrixXd M = solid::tet10_mass(X, density, solid::MassKind::Lumped);
    std::array<double, 10> m;
    for (int a = 0; a < 10; ++a) m[a] = M(3 * a, 3 * a);
    return m;
}

double element_omega_max(const Eigen::MatrixXd& K, std::span<const double> nodal_mass) {
    const int n = static_cast<int>(K.rows());
    Eigen::VectorXd s(n);
    for (int i = 0; i < n; ++i) {
        const double m = nodal_mass[i / 3];
        if (!(m > 0.0)) throw InputError("element_omega_max: non-positive nodal mass");
        s[i] = 1.0 / std::sqrt(m);
    }
    const Eigen::MatrixXd A = s.asDiagonal() * K * s.asDiagonal();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A, Eigen::EigenvaluesOnly);
    return std::sqrt(std::max(0.0, eig.eigenvalues()[n - 1]));
}

// --- the per-cycle kernel -------------------------------------------------------------------------

template <int N, int Q>
TetPacked<Q> pack(const Reference<N, Q>& ref) {
    TetPacked<Q> p;
    for (int q = 0; q < Q; ++q) {
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j) p.A[q][k][j] = ref.jinv[q](k, j);
        p.weight[q] = ref.weight[q];
    }
    p.length0 = std::cbrt(ref.volume);
    return p;
}
template TetPacked<1> pack(const Reference<4, 1>&);
template TetPacked<4> pack(const Reference<10, 4>&);

bool straight_sided(std::span<const Vec3> X) {
    if (X.size() != 10) return false;
    for (int e = 0; e < 6; ++e) {
        const Vec3& a = X[kEdge[e][0]];
        const Vec3& b = X[kEdge[e][1]];
        if ((X[4 + e] - 0.5 * (a + b)).norm() > kStraightTolerance * (b - a).norm()) return false;
    }
    return true;
}

TetPacked<1> pack_straight(const Reference<10, 4>& ref) {
    // Point 0's J0^-1 and w det J0 stand for all four (equal to round-off on a straight element).
    TetPacked<1> p;
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j) p.A[0][k][j] = ref.jinv[0](k, j);
    p.weight[0] = ref.weight[0];
    p.length0 = std::cbrt(ref.volume);
    return p;
}

template <int Q>
void pack_lane(const TetPacked<Q>& p, int l, TetPackedBlock<Q>& b) {
    for (int q = 0; q < Q; ++q) {
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j) b.A[q][k][j][l] = p.A[q][k][j];
        b.weight[q][l] = p.weight[q];
    }
    b.length0[l] = p.length0;
}
template void pack_lane(const TetPacked<1>&, int, TetPackedBlock<1>&);
template void pack_lane(const TetPacked<4>&, int, TetPackedBlock<4>&);

namespace {
using lanes::select;

// dN_a/dL_m of the tet10 at its point q (header): 4 L_m - 1 on the corners, 4 L for the edges.
// L_m = kRuleA at m = q, kRuleB elsewhere; the edges (i, j) in Gmsh order as kEdge.
inline double corner_factor(int q, int m) { return 4.0 * (m == q ? kRuleA : kRuleB) - 1.0; }
inline double edge_factor(int q, int m) { return 4.0 * (m == q ? kRuleA : kRuleB); }

// G_ik = sum_a u_a,i dN_a/dxi_k at point q, from the nodal values u[i][a].
template <int N, class T>
[[gnu::always_inline]] inline void natural_gradient(int q, const T (&u)[3][N], T (&G)[3][3]) {
    for (int i = 0; i < 3; ++i) {
        T c[4];  // c_m = sum_a u_a,i dN_a/dL_m
        if constexpr (N == 4) {
            for (int m = 0; m < 4; ++m) c[m] = u[i][m];
        } else {
            for (int m = 0; m < 4; ++m) c[m] = corner_factor(q, m) * u[i][m];
            for (int e = 0; e < 6; ++e) {
                const int a = kEdge[e][0], b = kEdge[e][1];
                c[a] += edge_factor(q, b) * u[i][4 + e];
                c[b] += edge_factor(q, a) * u[i][4 + e];
            }
        }
        for (int k = 0; k < 3; ++k) G[i][k] = c[k + 1] - c[0];
    }
}

// f_a += sum_m dN_a/dL_m s_m at point q, with s_{k+1},i = S_ik and s_0 = -(s_1 + s_2 + s_3).
template <int N, class T>
[[gnu::always_inline]] inline void add_nodal_forces(int q, const T (&S)[3][3], T (&f)[3][N]) {
    for (int i = 0; i < 3; ++i) {
        const T s[4] = {-(S[i][0] + S[i][1] + S[i][2]), S[i][0], S[i][1], S[i][2]};
        if constexpr (N == 4) {
            for (int m = 0; m < 4; ++m) f[i][m] += s[m];
        } else {
            for (int m = 0; m < 4; ++m) f[i][m] += corner_factor(q, m) * s[m];
            for (int e = 0; e < 6; ++e) {
                const int a = kEdge[e][0], b = kEdge[e][1];
                f[i][4 + e] += edge_factor(q, b) * s[a] + edge_factor(q, a) * s[b];
            }
        }
    }
}

// S = w P A^T.
template <class T>
[[gnu::always_inline]] inline void weighted_stress(const T& w, const T (&P)[3][3], const T (&A)[3][3], T (&S)[3][3]) {
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) S[i][k] = w * (P[i][0] * A[k][0] + P[i][1] * A[k][1] + P[i][2] * A[k][2]);
}

// Q points; the packed data has one J0^-1 and weight per point (P = Q) or one for all (P = 1: a
// straight-sided tet10, pack_straight).
template <int N, int Q, class T, int P>
[[gnu::always_inline]] inline void kernel(const TetPackedT<P, T>& p, const hex8::Hex8Material& mat,
                                          const T (&u)[3][N], const T (&v)[3][N], TetKernelResultT<N, T>& out,
                                          bool viscous_forces) {
    for (int i = 0; i < 3; ++i)
        for (int a = 0; a < N; ++a) out.f[i][a] = T{};
    if (viscous_forces)
        for (int i = 0; i < 3; ++i)
            for (int a = 0; a < N; ++a) out.fv[i][a] = T{};
    T energy{}, power{}, rate{}, volume{}, min_j{};
    T bsum[3][3];  // sum_q w_q b_q (upper triangle): the deviator of sum_q w_q J_q sigma_q is mu times its
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) bsum[i][j] = T{};
    for (int q = 0; q < Q; ++q) {
        const int pq = P == 1 ? 0 : q;
        const auto& A = p.A[pq];
        T G[3][3], Gd[3][3], H[3][3], Fd[3][3];
        natural_gradient<N>(q, u, G);
        natural_gradient<N>(q, v, Gd);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                H[i][j] = G[i][0] * A[0][j] + G[i][1] * A[1][j] + G[i][2] * A[2][j];
                Fd[i][j] = Gd[i][0] * A[0][j] + Gd[i][1] * A[1][j] + Gd[i][2] * A[2][j];
            }
        lanes::MaterialPoint<T> m;
        lanes::material_point(mat, H, Fd, p.length0, 0.0, m);
        const T w = p.weight[pq];
        min_j = q == 0 ? m.J : select(m.J < min_j, m.J, min_j);
        energy += w * m.W;
        const T wj = w * m.J;
        volume += wj;
        rate += wj * m.trD;
        power += wj * m.power;
        for (int i = 0; i < 3; ++i)
            for (int j = i; j < 3; ++j) bsum[i][j] += w * m.b[i][j];
        T S[3][3];
        weighted_stress(w, m.P, A, S);
        add_nodal_forces<N>(q, S, out.f);
        if (viscous_forces && m.viscous) {
            weighted_stress(w, m.Pv, A, S);
            add_nodal_forces<N>(q, S, out.fv);
        }
    }
    out.strain_energy = energy;
    out.viscous_power = power;
    out.volumetric_strain_rate = rate / volume;
    out.min_jacobian = min_j;
    const T sc = mat.mu / volume;
    out.von_mises_sq = sc * sc * lanes::von_mises_sq(bsum);
}

// Table 2-1 tetrahedron length on the corner nodes, as fem::cfl::tetrahedron_length: minimum
// altitude 3 V / largest face area; the largest area from the largest squared cross product (one
// square root: sqrt is monotone, so this is the same maximum).
template <class T>
[[gnu::always_inline]] inline T length_of(const T (&x)[3][4]) {
    // (The squared norm through a reference, not returned: a lambda returning a 64-byte vector
    // draws GCC's -Wpsabi note in the baseline clone, which no pragma silences.)
    auto cross_sq = [&](int a, int b, int c, T (&n)[3], T& sq) {
        T p[3], r[3];
        for (int i = 0; i < 3; ++i) {
            p[i] = x[i][b] - x[i][a];
            r[i] = x[i][c] - x[i][a];
        }
        n[0] = p[1] * r[2] - p[2] * r[1];
        n[1] = p[2] * r[0] - p[0] * r[2];
        n[2] = p[0] * r[1] - p[1] * r[0];
        sq = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    };
    T n[3], largest;
    cross_sq(0, 2, 3, n, largest);  // face opposite node 1; its normal gives the volume below
    const T e1[3] = {x[0][1] - x[0][0], x[1][1] - x[1][0], x[2][1] - x[2][0]};
    const T v6 = e1[0] * n[0] + e1[1] * n[1] + e1[2] * n[2];  // 6 V (signed)
    const T volume = select(v6 < 0.0, -v6, v6) / 6.0;
    for (const auto& f : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 1, 3}, std::array<int, 3>{1, 2, 3}}) {
        T a;
        cross_sq(f[0], f[1], f[2], n, a);
        largest = select(a > largest, a, largest);
    }
    return 3.0 * volume / (0.5 * lanes::sqrt_lanes(largest));
}
}  // namespace

void internal_force(const TetPacked<1>& p, const hex8::Hex8Material& mat, const double (&u)[3][4],
                    const double (&v)[3][4], TetKernelResult<4>& out, bool viscous_forces) {
    kernel<4, 1>(p, mat, u, v, out, viscous_forces);
}
void internal_force(const TetPacked<4>& p, const hex8::Hex8Material& mat, const double (&u)[3][10],
                    const double (&v)[3][10], TetKernelResult<10>& out, bool viscous_forces) {
    kernel<10, 4>(p, mat, u, v, out, viscous_forces);
}
void internal_force(const TetPacked<1>& p, const hex8::Hex8Material& mat, const double (&u)[3][10],
                    const double (&v)[3][10], TetKernelResult<10>& out, bool viscous_forces) {
    kernel<10, 4>(p, mat, u, v, out, viscous_forces);
}
FEM_KERNEL_CLONES
void internal_force(const TetPackedBlock<1>& p, const hex8::Hex8Material& mat, const hex8::Lanes (&u)[3][4],
                    const hex8::Lanes (&v)[3][4], TetKernelResultBlock<4>& out, bool viscous_forces) {
    kernel<4, 1>(p, mat, u, v, out, viscous_forces);
}
FEM_KERNEL_CLONES
void internal_force(const TetPackedBlock<4>& p, const hex8::Hex8Material& mat, const hex8::Lanes (&u)[3][10],
                    const hex8::Lanes (&v)[3][10], TetKernelResultBlock<10>& out, bool viscous_forces) {
    kernel<10, 4>(p, mat, u, v, out, viscous_forces);
}
FEM_KERNEL_CLONES
void internal_force(const TetPackedBlock<1>& p, const hex8::Hex8Material& mat, const hex8::Lanes (&u)[3][10],
                    const hex8::Lanes (&v)[3][10], TetKernelResultBlock<10>& out, bool viscous_forces) {
    kernel<10, 4>(p, mat, u, v, out, viscous_forces);
}

FEM_KERNEL_CLONES
void critical_time_step(const hex8::Lanes (&x)[3][4], const hex8::Lanes& trD, double c, const BulkViscosity& bulk,
                        hex8::Lanes& dt) {
    dt = lanes::solid_time_step(length_of(x), trD, c, bulk);
}

double characteristic_length(const double (&x)[3][4]) { return length_of(x); }

namespace {
// The tet10 length at the integration points (tet_explicit.hpp, critical_time_step_tet10): at each
// point q the corner tetrahedron mapped by J_q = J0 + G_q, G_q the kernel's parametric displacement
// gradient (natural_gradient), its Table 2-1 length by the tet4's own rule (length_of) on the
// mapped corners (0, J_q e_1, J_q e_2, J_q e_3).
template <class T>
[[gnu::always_inline]] inline T length_tet10(const T (&x)[3][4], const T (&u)[3][10]) {
    T shortest{};
    for (int q = 0; q < 4; ++q) {
        T G[3][3];
        natural_gradient<10>(q, u, G);
        T mapped[3][4];
        for (int i = 0; i < 3; ++i) {
            mapped[i][0] = T{};
            // J0's column k: the reference corner edge X_{k+1} - X_0 (X = x - u).
            for (int k = 0; k < 3; ++k) mapped[i][k + 1] = (x[i][k + 1] - u[i][k + 1]) - (x[i][0] - u[i][0]) + G[i][k];
        }
        const T h = length_of(mapped);
        shortest = q == 0 ? h : select(h < shortest, h, shortest);
    }
    return shortest;
}
}  // namespace

FEM_KERNEL_CLONES
void critical_time_step_tet10(const hex8::Lanes (&x)[3][4], const hex8::Lanes (&u)[3][10], const hex8::Lanes& trD, double c,
                              const BulkViscosity& bulk, hex8::Lanes& dt) {
    dt = lanes::solid_time_step(length_tet10(x, u), trD, c, bulk);
}

double characteristic_length_tet10(const double (&x)[3][4], const double (&u)[3][10]) { return length_tet10(x, u); }

template <int N>
void gather(const double* xs, const double* Xs, const double* vs, const std::array<int, N>* conn, int lanes,
            hex8::Lanes (&x)[3][4], hex8::Lanes (&u)[3][N], hex8::Lanes (&v)[3][N]) {
    hex8::gather_lanes<N, 4>(xs, Xs, vs, conn, lanes, x, u, v);  // element/lane_gather.hpp: the corners' x only
}
template void gather<4>(const double*, const double*, const double*, const std::array<int, 4>*, int, hex8::Lanes (&)[3][4],
                        hex8::Lanes (&)[3][4], hex8::Lanes (&)[3][4]);
template void gather<10>(const double*, const double*, const double*, const std::array<int, 10>*, int, hex8::Lanes (&)[3][4],
                         hex8::Lanes (&)[3][10], hex8::Lanes (&)[3][10]);

template void internal_force<4, 1>(const Reference<4, 1>&, const hex8::Hex8Material&, std::span<const Vec3>,
                                   std::span<const Vec3>, Result<4>&);
template void internal_force<10, 4>(const Reference<10, 4>&, const hex8::Hex8Material&, std::span<const Vec3>,
                                    std::span<const Vec3>, Result<10>&);
template Eigen::MatrixXd linear_stiffness<4, 1>(const Reference<4, 1>&, const hex8::Hex8Material&);
template Eigen::MatrixXd linear_stiffness<10, 4>(const Reference<10, 4>&, const hex8::Hex8Material&);

}  // namespace fem::tet
