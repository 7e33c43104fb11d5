#include "element/tet_explicit.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "core/error.hpp"
#include "element/solid_elements.hpp"

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
        const Mat3 jinvt = J.inverse().transpose();
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

Tet10Reference make_tet10_reference(std::span<const Vec3> X, const char* element_name) {
    // 4-point rule of degree 2: barycentric (a, b, b, b) and permutations, weights 1/24.
    const double a = 0.5854101966249685, b = 0.1381966011250105;
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

template void internal_force<4, 1>(const Reference<4, 1>&, const hex8::Hex8Material&, std::span<const Vec3>,
                                   std::span<const Vec3>, Result<4>&);
template void internal_force<10, 4>(const Reference<10, 4>&, const hex8::Hex8Material&, std::span<const Vec3>,
                                    std::span<const Vec3>, Result<10>&);
template Eigen::MatrixXd linear_stiffness<4, 1>(const Reference<4, 1>&, const hex8::Hex8Material&);
template Eigen::MatrixXd linear_stiffness<10, 4>(const Reference<10, 4>&, const hex8::Hex8Material&);

}  // namespace fem::tet
