#include "element/hex8_explicit.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"

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
    return h;
}

double von_mises(const Mat3& s) {
    const double a = s(0, 0) - s(1, 1), b = s(1, 1) - s(2, 2), c = s(2, 2) - s(0, 0);
    return std::sqrt(0.5 * (a * a + b * b + c * c) +
                     3.0 * (s(0, 1) * s(0, 1) + s(1, 2) * s(1, 2) + s(0, 2) * s(0, 2)));
}

void internal_force(const Hex8Reference& ref, const Hex8Material& mat, const std::array<Vec3, 8>& u,
                    const std::array<Vec3, 8>& v, double length, Hex8Result& out) {
    // Displacement gradient H = F - I from the displacements (not the positions): the strain, the
    // stored energy and the hourglass displacements keep full precision at small strain and far
    // from the origin.
    const double inv_v0 = 1.0 / ref.volume;
    Mat3 H = Mat3::Zero(), Fdot = Mat3::Zero();
    for (int a = 0; a < 8; ++a) {
        H.noalias() += u[a] * ref.B[a].transpose();
        Fdot.noalias() += v[a] * ref.B[a].transpose();
    }
    H *= inv_v0;
    Fdot *= inv_v0;
    const Mat3 F = Mat3::Identity() + H;
    // J - 1 = det(I + H) - 1 = tr H + (tr^2 H - tr H^2)/2 + det H, without cancellation.
    const double trH = H.trace();
    const double jm1 = trH + 0.5 * (trH * trH - (H * H).trace()) + H.determinant();
    const double J = 1.0 + jm1;
    out.jacobian = J;
    if (!(J > 0.0)) {
        out.inverted = true;
        return;
    }
    out.inverted = false;
    const Mat3 Finv = F.inverse();
    const Mat3 FinvT = Finv.transpose();
    const double lnJ = std::log1p(jm1);
    const double mu = mat.mu, lambda = mat.lambda;

    // Neo-Hookean first Piola-Kirchhoff stress and stored energy.
    Mat3 P = mu * (F - FinvT) + (lambda * lnJ) * FinvT;
    // W = mu/2 (I1 - 3 - 2 ln J) + lambda/2 ln^2 J with I1 - 3 = 2 tr H + |H|^2.
    out.strain_energy =
        ref.volume * (0.5 * mu * (2.0 * (trH - lnJ) + H.squaredNorm()) + 0.5 * lambda * lnJ * lnJ);
    out.cauchy = (P * F.transpose()) / J;
    out.von_mises = von_mises(out.cauchy);

    // Viscous Cauchy stresses from the velocity gradient L = Fdot F^-1 (current configuration).
    const Mat3 L = Fdot * Finv;
    const double trD = L.trace();
    out.volumetric_strain_rate = trD;
    Mat3 sv = Mat3::Zero();
    bool viscous = false;
    if (mat.bulk_viscosity && trD < 0.0) {
        // Table 2-1 / LS-DYNA bulk viscosity: q = rho l (C0 l eps_kk^2 - C1 c eps_kk), a pressure,
        // with l the cube root of the current volume (LS-DYNA's choice for solids) unless given.
        if (!(length > 0.0)) length = std::cbrt(J * ref.volume);
        const double rho = mat.density / J;
        const double c = std::sqrt((lambda + 2.0 * mu) / mat.density);
        const double q = rho * length * (mat.bulk.quadratic * length * trD * trD - mat.bulk.linear * c * trD);
        sv.diagonal().array() -= q;
        viscous = true;
    }
    if (mat.rayleigh_beta > 0.0) {
        // beta K v of Eq 2-39 as a viscous stress beta C : D (the tangent of the material at rest).
        const Mat3 D = 0.5 * (L + L.transpose());
        sv += mat.rayleigh_beta * (2.0 * mu * D);
        sv.diagonal().array() += mat.rayleigh_beta * lambda * trD;
        viscous = true;
    }
    if (viscous) {
        const Mat3 D = 0.5 * (L + L.transpose());
        out.viscous_power = J * ref.volume * (sv.cwiseProduct(D)).sum();
        P.noalias() += J * sv * FinvT;
    } else {
        out.viscous_power = 0.0;
    }

    for (int a = 0; a < 8; ++a) out.force[a].noalias() = P * ref.B[a];

    // Flanagan-Belytschko stiffness hourglass control (see the header).
    const double k = mat.hourglass_qm * 2.0 * mu * ref.hourglass_norm / 8.0;
    double e_hg = 0.0;
    if (k > 0.0) {
        for (int al = 0; al < 4; ++al) {
            const auto& g = ref.gamma[al];
            Vec3 q = Vec3::Zero();
            for (int a = 0; a < 8; ++a) q += g[a] * u[a];  // = sum gamma x: gamma is orthogonal to constants
            e_hg += q.squaredNorm();
            const Vec3 kq = k * q;
            for (int a = 0; a < 8; ++a) out.force[a] += g[a] * kq;
        }
    }
    out.hourglass_energy = 0.5 * k * e_hg;
}

}  // namespace fem::hex8
