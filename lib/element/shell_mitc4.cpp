#include "element/shell_mitc4.hpp"

#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include "core/error.hpp"

namespace fem::shell {

namespace {

// Parametric coordinates of the corner nodes (counter-clockwise).
constexpr double node_r[4] = {-1.0, 1.0, 1.0, -1.0};
constexpr double node_s[4] = {-1.0, -1.0, 1.0, 1.0};

struct Shape {
    double h[4], hr[4], hs[4];  // bilinear shape functions and their r, s derivatives
};

Shape shape(double r, double s) {
    Shape f;
    for (int k = 0; k < 4; ++k) {
        f.h[k] = 0.25 * (1 + node_r[k] * r) * (1 + node_s[k] * s);
        f.hr[k] = 0.25 * node_r[k] * (1 + node_s[k] * s);
        f.hs[k] = 0.25 * node_s[k] * (1 + node_r[k] * r);
    }
    return f;
}

// [v]_x: the matrix with [v]_x a = v x a.
Mat3 skew(const Vec3& v) {
    Mat3 m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
}

using Op = Eigen::Matrix<double, 3, 24>;   // maps the 24 nodal DOF to a 3-vector
using Row = Eigen::Matrix<double, 1, 24>;  // maps the 24 nodal DOF to a scalar

// Mid-surface tangents x_r, x_s at (r, s).
std::pair<Vec3, Vec3> tangents(const std::array<Vec3, 4>& x, double r, double s) {
    const Shape f = shape(r, s);
    Vec3 ar = Vec3::Zero(), as = Vec3::Zero();
    for (int k = 0; k < 4; ++k) {
        ar += f.hr[k] * x[k];
        as += f.hs[k] * x[k];
    }
    return {ar, as};
}

// Geometry and displacement-derivative operators at one point (r, s, z) of the shell volume:
// J = [g_r g_s g_z] (covariant base vectors as columns) and U_i = d u / d r_i as operators on the DOF.
struct PointOps {
    Mat3 J;
    Op Ur, Us, Uz;
};

PointOps point_ops(const std::array<Vec3, 4>& x, const std::array<Vec3, 4>& V, const std::array<Mat3, 4>& R,
                   double half_t, double r, double s, double z) {
    const Shape f = shape(r, s);
    PointOps p;
    Vec3 gr = Vec3::Zero(), gs = Vec3::Zero(), gz = Vec3::Zero();
    p.Ur.setZero();
    p.Us.setZero();
    p.Uz.setZero();
    for (int k = 0; k < 4; ++k) {
        const Vec3 xk = x[k] + z * half_t * V[k];
        gr += f.hr[k] * xk;
        gs += f.hs[k] * xk;
        gz += f.h[k] * half_t * V[k];
        // u = sum h_k (u_k + z t/2 R_k theta_k), R_k theta = theta x V_k
        p.Ur.block<3, 3>(0, 6 * k).diagonal().setConstant(f.hr[k]);
        p.Us.block<3, 3>(0, 6 * k).diagonal().setConstant(f.hs[k]);
        p.Ur.block<3, 3>(0, 6 * k + 3) = f.hr[k] * z * half_t * R[k];
        p.Us.block<3, 3>(0, 6 * k + 3) = f.hs[k] * z * half_t * R[k];
        p.Uz.block<3, 3>(0, 6 * k + 3) = f.h[k] * half_t * R[k];
    }
    p.J.col(0) = gr;
    p.J.col(1) = gs;
    p.J.col(2) = gz;
    return p;
}

// Covariant strain component e_ij = (g_i . u_,j + g_j . u_,i) / 2 as a row operator.
Row covariant(const PointOps& p, int i, int j) {
    const Op* U[3] = {&p.Ur, &p.Us, &p.Uz};
    return 0.5 * (p.J.col(i).transpose() * *U[j] + p.J.col(j).transpose() * *U[i]);
}

void refuse(const std::string& what) { throw InputError("MITC4 shell element: " + what); }

}  // namespace

std::array<Vec3, 4> mitc4_directors(const std::array<Vec3, 4>& x) {
    std::array<Vec3, 4> V;
    for (int k = 0; k < 4; ++k) {
        const auto [ar, as] = tangents(x, node_r[k], node_s[k]);
        const Vec3 n = ar.cross(as);
        const double scale = ar.norm() * as.norm();
        if (!(n.norm() > 1e-12 * scale) || !(scale > 0)) {
            std::ostringstream msg;
            msg << "degenerate element: the two edges at node " << k << " are parallel or of zero length";
            refuse(msg.str());
        }
        V[k] = n.normalized();
    }
    return V;
}

ShellMatrices mitc4_matrices(const std::array<Vec3, 4>& x, double thickness, const ElasticMaterial& material,
                             const Mitc4Options& options) {
    if (!(thickness > 0) || !std::isfinite(thickness)) {
        std::ostringstream msg;
        msg << "thickness " << thickness << " must be positive";
        refuse(msg.str());
    }
    for (int k = 0; k < 4; ++k)
        if (!x[k].allFinite()) refuse("node " + std::to_string(k) + " has a non-finite coordinate");

    const std::array<Vec3, 4> V = mitc4_directors(x);
    // A non-convex or inverted quadrilateral shows as a director pointing against the others.
    const Vec3 n_mean = (V[0] + V[1] + V[2] + V[3]).normalized();
    for (int k = 0; k < 4; ++k)
        if (V[k].dot(n_mean) < 0.2)
            refuse("inverted, non-convex or strongly warped element (normal at node " + std::to_string(k) +
                   " turns away from the element's mean normal)");

    std::array<Mat3, 4> R;
    for (int k = 0; k < 4; ++k) R[k] = -skew(V[k]);  // R_k theta = theta x V_k

    const double t = thickness, half_t = 0.5 * thickness;
    const double E = material.youngs_modulus, nu = material.poissons_ratio, rho = material.density;
    const double G = material.shear_modulus();
    constexpr double shear_correction = 5.0 / 6.0;

    // Plane-stress material in the local frame: (eps11, eps22, gamma12, gamma13, gamma23).
    Eigen::Matrix<double, 5, 5> D = Eigen::Matrix<double, 5, 5>::Zero();
    const double c = E / (1 - nu * nu);
    D(0, 0) = D(1, 1) = c;
    D(0, 1) = D(1, 0) = c * nu;
    D(2, 2) = G;
    D(3, 3) = D(4, 4) = shear_correction * G;

    ShellMatrices out;
    out.stiffness.setZero();
    out.consistent_mass.setZero();
    out.lumped_mass.setZero();

    const double gp = 1.0 / std::sqrt(3.0);
    const double gauss[2] = {-gp, gp};  // weights 1

    // Tributary areas A_k = integral h_k dA of the mid-surface (2x2 Gauss).
    std::array<double, 4> nodal_area{0, 0, 0, 0};
    for (double r : gauss)
        for (double s : gauss) {
            const auto [ar, as] = tangents(x, r, s);
            const double dA = ar.cross(as).norm();
            const Shape f = shape(r, s);
            for (int k = 0; k < 4; ++k) nodal_area[k] += f.h[k] * dA;
        }
    out.area = nodal_area[0] + nodal_area[1] + nodal_area[2] + nodal_area[3];

    for (double z : gauss) {
        // Tying points of the assumed transverse shear (Dvorkin-Bathe): e_rz at A (0, 1) and C (0, -1),
        // e_sz at D (1, 0) and B (-1, 0), at the same thickness coordinate.
        const Row erz_A = covariant(point_ops(x, V, R, half_t, 0, 1, z), 0, 2);
        const Row erz_C = covariant(point_ops(x, V, R, half_t, 0, -1, z), 0, 2);
        const Row esz_D = covariant(point_ops(x, V, R, half_t, 1, 0, z), 1, 2);
        const Row esz_B = covariant(point_ops(x, V, R, half_t, -1, 0, z), 1, 2);

        for (double r : gauss)
            for (double s : gauss) {
                const PointOps p = point_ops(x, V, R, half_t, r, s, z);
                const double detJ = p.J.determinant();
                if (!(detJ > 0)) refuse("non-positive Jacobian: inverted or degenerate element");

                // Covariant strains: in-plane and e_zz from the displacement field, transverse shear
                // from the tying points.
                Row e[3][3];
                e[0][0] = covariant(p, 0, 0);
                e[1][1] = covariant(p, 1, 1);
                e[2][2] = covariant(p, 2, 2);
                e[0][1] = covariant(p, 0, 1);
                e[0][2] = 0.5 * (1 + s) * erz_A + 0.5 * (1 - s) * erz_C;
                e[1][2] = 0.5 * (1 + r) * esz_D + 0.5 * (1 - r) * esz_B;
                e[1][0] = e[0][1];
                e[2][0] = e[0][2];
                e[2][1] = e[1][2];

                // Local orthonormal frame: e3 the mid-surface normal, e1 along x_r.
                const auto [ar, as] = tangents(x, r, s);
                const Vec3 e3 = ar.cross(as).normalized();
                const Vec3 e1 = (ar - ar.dot(e3) * e3).normalized();
                const Vec3 e2 = e3.cross(e1);
                Mat3 Q;
                Q.col(0) = e1;
                Q.col(1) = e2;
                Q.col(2) = e3;
                // eps_ab = sum_ij e_ij (g^i . e_a)(g^j . e_b); g^i are the rows of J^-1.
                const Mat3 T = Q.transpose() * p.J.inverse().transpose();  // T(a, i) = e_a . g^i
                auto local = [&](int a, int b) {
                    Row v = Row::Zero();
                    for (int i = 0; i < 3; ++i)
                        for (int j = 0; j < 3; ++j) v += T(a, i) * T(b, j) * e[i][j];
                    return v;
                };
                Eigen::Matrix<double, 5, 24> B;
                B.row(0) = local(0, 0);
                B.row(1) = local(1, 1);
                B.row(2) = 2 * local(0, 1);
                B.row(3) = 2 * local(0, 2);
                B.row(4) = 2 * local(1, 2);
                out.stiffness.noalias() += B.transpose() * D * B * detJ;

                // Consistent mass: N = sum h_k [I | z t/2 R_k].
                const Shape f = shape(r, s);
                Op N = Op::Zero();
                for (int k = 0; k < 4; ++k) {
                    N.block<3, 3>(0, 6 * k).diagonal().setConstant(f.h[k]);
                    N.block<3, 3>(0, 6 * k + 3) = f.h[k] * z * half_t * R[k];
                }
                out.consistent_mass.noalias() += rho * N.transpose() * N * detJ;
            }
    }

    // Drilling penalty and drilling inertia, node by node.
    const double rotary = rho * t * t * t / 12.0;
    for (int k = 0; k < 4; ++k) {
        const Shape f = shape(node_r[k], node_s[k]);
        const auto [ar, as] = tangents(x, node_r[k], node_s[k]);
        const double a = ar.cross(as).norm();
        Row constraint = Row::Zero();
        for (int j = 0; j < 4; ++j) {
            // membrane in-plane rotation (u_r . x_s - u_s . x_r) / (2 |x_r x x_s|)
            constraint.segment<3>(6 * j) -= (f.hr[j] * as - f.hs[j] * ar).transpose() / (2 * a);
        }
        constraint.segment<3>(6 * k + 3) += V[k].transpose();
        const double k_drill = options.drilling_factor * G * t * nodal_area[k];
        out.stiffness.noalias() += k_drill * constraint.transpose() * constraint;
        out.consistent_mass.block<3, 3>(6 * k + 3, 6 * k + 3) += rotary * nodal_area[k] * V[k] * V[k].transpose();

        // Lumped mass: translational rho t A_k, rotational rho t^3/12 A_k (scaled) about every axis.
        for (int d = 0; d < 3; ++d) {
            out.lumped_mass(6 * k + d, 6 * k + d) = rho * t * nodal_area[k];
            out.lumped_mass(6 * k + 3 + d, 6 * k + 3 + d) = options.rotary_inertia_scale * rotary * nodal_area[k];
        }
    }
    // Symmetrize away round-off so that eigen-solvers see exactly symmetric matrices.
    out.stiffness = 0.5 * (out.stiffness + out.stiffness.transpose()).eval();
    out.consistent_mass = 0.5 * (out.consistent_mass + out.consistent_mass.transpose()).eval();
    return out;
}

}  // namespace fem::shell
