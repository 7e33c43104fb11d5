#include "element/shell_bt_explicit.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"
#include "element/critical_time_step.hpp"

namespace fem::shellbt {

void ShellSection::validate(const char* owner) const {
    auto bad = [](double v) { return !std::isfinite(v) || v < 0.0; };
    if (!(thickness > 0.0) || !std::isfinite(thickness))
        throw InputError(fmt::format("{}: shell thickness {} must be positive", owner, thickness));
    if (!(shear_factor > 0.0) || !std::isfinite(shear_factor))
        throw InputError(fmt::format("{}: transverse shear factor {} must be positive", owner, shear_factor));
    if (bad(hourglass_membrane) || bad(hourglass_bending) || bad(hourglass_transverse) || bad(drilling))
        throw InputError(fmt::format("{}: hourglass coefficients (membrane {}, bending {}, transverse {}) and the "
                                     "drilling coefficient {} must not be negative",
                                     owner, hourglass_membrane, hourglass_bending, hourglass_transverse, drilling));
}

Constants Constants::from(const ElasticMaterial& m, const ShellSection& s) {
    Constants c;
    c.E = m.youngs_modulus;
    c.nu = m.poissons_ratio;
    c.G = m.shear_modulus();
    c.rho = m.density;
    c.c11 = c.E / (1.0 - c.nu * c.nu);
    c.c12 = c.nu * c.c11;
    c.kappa_G = s.shear_factor * c.G;
    c.t = s.thickness;
    c.r_m = s.hourglass_membrane;
    c.r_theta = s.hourglass_bending;
    c.r_w = s.hourglass_transverse;
    c.r_d = s.drilling;
    return c;
}

Frame make_frame(const std::array<Vec3, 4>& x) {
    Frame f;
    const Vec3 s3 = (x[2] - x[0]).cross(x[3] - x[1]);
    const double n3 = s3.norm();
    f.area = 0.5 * n3;
    if (!(f.area > 0.0) || !std::isfinite(f.area)) {
        f.area = 0.0;
        return f;
    }
    const Vec3 e3 = s3 / n3;
    const Vec3 r21 = x[1] - x[0];
    Vec3 e1 = r21 - r21.dot(e3) * e3;
    const double n1 = e1.norm();
    if (!(n1 > 0.0)) {  // side 1-2 of zero length (or along the normal): a degenerate element
        f.area = 0.0;
        return f;
    }
    e1 /= n1;
    const Vec3 e2 = e3.cross(e1);
    f.E.col(0) = e1;
    f.E.col(1) = e2;
    f.E.col(2) = e3;
    const Vec3 c = 0.25 * (x[0] + x[1] + x[2] + x[3]);
    auto& px = f.px;
    auto& py = f.py;
    for (int I = 0; I < 4; ++I) {
        const Vec3 d = x[I] - c;
        px[I] = e1.dot(d);
        py[I] = e2.dot(d);
        f.warp[I] = e3.dot(d);
    }
    f.triangle = (x[3] - x[2]).squaredNorm() == 0.0;
    if (f.triangle) {
        // MITC3 fit of the transverse shear to the three edges' tangential strains: at edge e's
        // midpoint m, s . (a1 + c y, a2 - c x) = sx a1 + sy a2 + c (sx y_m - sy x_m) = e_s(e).
        const double xc = (px[0] + px[1] + px[2]) / 3, yc = (py[0] + py[1] + py[2]) / 3;
        Mat3 T;
        for (int e = 0; e < 3; ++e) {
            const int i = e, j = (e + 1) % 3;
            const double dx = px[j] - px[i], dy = py[j] - py[i];
            f.len[e] = std::sqrt(dx * dx + dy * dy);
            f.sx[e] = dx / f.len[e];
            f.sy[e] = dy / f.len[e];
            const double xm = 0.5 * (px[i] + px[j]) - xc, ym = 0.5 * (py[i] + py[j]) - yc;
            T.row(e) << f.sx[e], f.sy[e], f.sx[e] * ym - f.sy[e] * xm;
        }
        const Mat3 Ti = T.inverse();
        for (int r = 0; r < 2; ++r)
            for (int e = 0; e < 3; ++e) f.shear[r][e] = Ti(r, e);
    }
    const double inv = 1.0 / (2.0 * f.area);
    f.b1 = {(py[1] - py[3]) * inv, (py[2] - py[0]) * inv, (py[3] - py[1]) * inv, (py[0] - py[2]) * inv};
    f.b2 = {(px[3] - px[1]) * inv, (px[0] - px[2]) * inv, (px[1] - px[3]) * inv, (px[2] - px[0]) * inv};
    // Hourglass vector h = (1, -1, 1, -1) minus its linear part (Belytschko-Tsay / Flanagan-Belytschko).
    const double hx = px[0] - px[1] + px[2] - px[3], hy = py[0] - py[1] + py[2] - py[3];
    static constexpr double h[4] = {1.0, -1.0, 1.0, -1.0};
    f.bb = 0.0;
    for (int I = 0; I < 4; ++I) {
        f.gamma[I] = h[I] - hx * f.b1[I] - hy * f.b2[I];
        f.bb += f.b1[I] * f.b1[I] + f.b2[I] * f.b2[I];
        f.gxx += f.gamma[I] * px[I] * px[I];
        f.gyy += f.gamma[I] * py[I] * py[I];
        f.gxy += f.gamma[I] * px[I] * py[I];
    }
    return f;
}

Vec3 rotation_increment(const Mat3& R_new, const Mat3& R_old) {
    const Mat3 dR = R_new * R_old.transpose();
    // w = sin(phi) n (skew part); 2 tan(phi/2) n = 2 w / (1 + cos phi) = 4 w / (1 + tr dR).
    const Vec3 w(0.5 * (dR(2, 1) - dR(1, 2)), 0.5 * (dR(0, 2) - dR(2, 0)), 0.5 * (dR(1, 0) - dR(0, 1)));
    return (4.0 / (1.0 + dR.trace())) * w;
}

namespace {
// Hourglass stiffnesses (bending x2, transverse, membrane x2) on a frame.
std::array<double, 5> hourglass_stiffness(const Constants& c, const Frame& f) {
    const double t3 = c.t * c.t * c.t;
    const double kth = c.r_theta * c.E * t3 * f.area / 192.0 * f.bb;
    const double kw = c.r_w * c.kappa_G * t3 / 12.0 * f.bb;
    const double km = c.r_m * c.E * c.t * f.area / 8.0 * f.bb;
    return {kth, kth, kw, km, km};
}

// Drilling penalty per node, r_d G t A / 4.
double drilling_stiffness(const Constants& c, const Frame& f) { return c.r_d * c.G * c.t * f.area / 4.0; }

// Twice the in-plane spin at the centre, B_1I du^y_I - B_2I du^x_I (local increments u[I][d]).
double em_spin(const Frame& f, const double (&u)[4][3]) {
    double w = 0.0;
    for (int I = 0; I < 4; ++I) w += f.b1[I] * u[I][1] - f.b2[I] * u[I][0];
    return w;
}
}  // namespace

void update_state(const Constants& c, const Frame& mid, const std::array<Vec3, 4>& du,
                  const std::array<Vec3, 4>& dtheta, State& st) {
    const Mat3 Et = mid.E.transpose();
    double u[4][3], th[4][3];
    for (int I = 0; I < 4; ++I) {
        const Vec3 lu = Et * du[I], lt = Et * dtheta[I];
        for (int d = 0; d < 3; ++d) {
            u[I][d] = lu[d];
            th[I][d] = lt[d];
        }
    }
    // Warping correction (header): remove the in-plane motion of the offset nodes that the
    // element's rotation about its in-plane axes causes.
    double phi_x = 0.0, phi_y = 0.0;
    for (int I = 0; I < 4; ++I) {
        phi_x += mid.b2[I] * u[I][2];
        phi_y -= mid.b1[I] * u[I][2];
    }
    for (int I = 0; I < 4; ++I) {
        u[I][0] -= mid.warp[I] * phi_y;
        u[I][1] += mid.warp[I] * phi_x;
    }
    double em[3] = {0, 0, 0}, k[3] = {0, 0, 0}, g[2] = {0, 0}, sum_thx = 0, sum_thy = 0;
    double q[5] = {0, 0, 0, 0, 0};
    for (int I = 0; I < 4; ++I) {
        const double b1 = mid.b1[I], b2 = mid.b2[I], gm = mid.gamma[I];
        em[0] += b1 * u[I][0];
        em[1] += b2 * u[I][1];
        em[2] += b2 * u[I][0] + b1 * u[I][1];
        k[0] += b1 * th[I][1];
        k[1] -= b2 * th[I][0];
        k[2] += b2 * th[I][1] - b1 * th[I][0];
        g[0] += b1 * u[I][2];
        g[1] += b2 * u[I][2];
        sum_thx += th[I][0];
        sum_thy += th[I][1];
        q[0] += gm * th[I][0];
        q[1] += gm * th[I][1];
        q[2] += gm * u[I][2];
        q[3] += gm * u[I][0];
        q[4] += gm * u[I][1];
    }
    if (mid.triangle) {
        // Edge-based (MITC3) shear at the centroid instead of the one-point value (header).
        g[0] = g[1] = 0.0;
        for (int e = 0; e < 3; ++e) {
            const int i = e, j = (e + 1) % 3;
            const double es = (u[j][2] - u[i][2]) / mid.len[e] +
                              0.5 * (mid.sx[e] * (th[i][1] + th[j][1]) - mid.sy[e] * (th[i][0] + th[j][0]));
            g[0] += mid.shear[0][e] * es;
            g[1] += mid.shear[1][e] * es;
        }
    } else {
        g[0] += 0.25 * sum_thy;
        g[1] -= 0.25 * sum_thx;
    }
    // Transverse hourglass relative to the w the rotation gradients imply (header).
    {
        double b1tx = 0, b1ty = 0, b2tx = 0, b2ty = 0;
        for (int I = 0; I < 4; ++I) {
            b1tx += mid.b1[I] * th[I][0];
            b1ty += mid.b1[I] * th[I][1];
            b2tx += mid.b2[I] * th[I][0];
            b2ty += mid.b2[I] * th[I][1];
        }
        q[2] -= 0.5 * (-b1ty * mid.gxx + b2tx * mid.gyy + (b1tx - b2ty) * mid.gxy);
    }
    for (int p = 0; p < kPoints; ++p) {
        const double z = kPointZ[p] * c.t;
        const double e0 = em[0] + z * k[0], e1 = em[1] + z * k[1], e2 = em[2] + z * k[2];
        st.sigma[p][0] += c.c11 * e0 + c.c12 * e1;
        st.sigma[p][1] += c.c12 * e0 + c.c11 * e1;
        st.sigma[p][2] += c.G * e2;
    }
    st.tau[0] += c.kappa_G * g[0];
    st.tau[1] += c.kappa_G * g[1];
    const auto kh = hourglass_stiffness(c, mid);
    for (int i = 0; i < 5; ++i) st.hourglass[i] += kh[i] * q[i];
    if (c.r_d > 0.0) {
        // Drilling penalty: each node's rotation about the normal against the in-plane spin.
        const double kd = drilling_stiffness(c, mid);
        const double spin = 0.5 * (em_spin(mid, u));
        for (int I = 0; I < 4; ++I) st.drilling[I] += kd * (th[I][2] - spin);
    }
}

void forces(const Constants& c, const Frame& f, const State& st, Result& out) {
    // Resultants (Lobatto rule) and the elastic energy density per area.
    double N[3] = {0, 0, 0}, M[3] = {0, 0, 0}, w_el = 0.0;
    for (int p = 0; p < kPoints; ++p) {
        const double w = kPointWeight[p] * c.t, z = kPointZ[p] * c.t;
        const double* s = st.sigma[p];
        for (int i = 0; i < 3; ++i) {
            N[i] += w * s[i];
            M[i] += w * z * s[i];
        }
        // sigma . C^-1 sigma / 2 of plane stress
        w_el += w * ((s[0] * s[0] + s[1] * s[1] - 2.0 * c.nu * s[0] * s[1]) / (2.0 * c.E) + s[2] * s[2] / (2.0 * c.G));
        out.von_mises_sq[p] = s[0] * s[0] + s[1] * s[1] - s[0] * s[1] + 3.0 * s[2] * s[2];
    }
    // The transverse shear stress is shown at the mid-surface only (it vanishes on the free surfaces).
    out.von_mises_sq[1] += 3.0 * (st.tau[0] * st.tau[0] + st.tau[1] * st.tau[1]);
    const double Qx = c.t * st.tau[0], Qy = c.t * st.tau[1];
    w_el += c.t * (st.tau[0] * st.tau[0] + st.tau[1] * st.tau[1]) / (2.0 * c.kappa_G);
    const double A = f.area;
    out.strain_energy = A * w_el;
    const auto kh = hourglass_stiffness(c, f);
    out.hourglass_energy = 0.0;
    for (int i = 0; i < 5; ++i)
        if (kh[i] > 0.0) out.hourglass_energy += 0.5 * st.hourglass[i] * st.hourglass[i] / kh[i];
    const double* Q = st.hourglass;
    const double md = 0.5 * (st.drilling[0] + st.drilling[1] + st.drilling[2] + st.drilling[3]);
    if (c.r_d > 0.0) {
        const double kd = drilling_stiffness(c, f);
        for (int I = 0; I < 4; ++I) out.hourglass_energy += 0.5 * st.drilling[I] * st.drilling[I] / kd;
    }
    // Transverse shear: one-point (quadrilaterals: f^z = A B Q, moments A Q / 4 below), or the
    // conjugates of the triangle's edge strains (shear forces and moments per node, local).
    const double shear_share = f.triangle ? 0.0 : 0.25;
    double tz[4] = {0, 0, 0, 0}, tmx[4] = {0, 0, 0, 0}, tmy[4] = {0, 0, 0, 0};
    if (f.triangle) {
        for (int e = 0; e < 3; ++e) {
            const int i = e, j = (e + 1) % 3;
            const double Fe = A * (Qx * f.shear[0][e] + Qy * f.shear[1][e]);
            tz[j] += Fe / f.len[e];
            tz[i] -= Fe / f.len[e];
            for (int k : {i, j}) {
                tmy[k] += 0.5 * Fe * f.sx[e];
                tmx[k] -= 0.5 * Fe * f.sy[e];
            }
        }
    } else {
        for (int I = 0; I < 4; ++I) tz[I] = A * (f.b1[I] * Qx + f.b2[I] * Qy);
    }
    Vec3 fl[4];
    double sx = 0.0, sy = 0.0;  // sum_I z^_I f^x_I, sum_I z^_I f^y_I (warping correction)
    for (int I = 0; I < 4; ++I) {
        const double b1 = f.b1[I], b2 = f.b2[I], gm = f.gamma[I];
        fl[I] = Vec3(A * (b1 * N[0] + b2 * N[2]) + gm * Q[3] + b2 * md, A * (b2 * N[1] + b1 * N[2]) + gm * Q[4] - b1 * md,
                     tz[I] + gm * Q[2]);
        sx += f.warp[I] * fl[I].x();
        sy += f.warp[I] * fl[I].y();
    }
    for (int I = 0; I < 4; ++I) {
        const double b1 = f.b1[I], b2 = f.b2[I], gm = f.gamma[I];
        fl[I].z() += b1 * sx + b2 * sy;
        // Moments: bending, shear, bending hourglass, and the rotation part of the transverse
        // hourglass (conjugate of its theta terms).
        const Vec3 ml(-A * (b2 * M[1] + b1 * M[2] + shear_share * Qy) + tmx[I] + gm * Q[0] -
                          0.5 * Q[2] * (b2 * f.gyy + b1 * f.gxy),
                      A * (b1 * M[0] + b2 * M[2] + shear_share * Qx) + tmy[I] + gm * Q[1] +
                          0.5 * Q[2] * (b1 * f.gxx + b2 * f.gxy),
                      st.drilling[I]);
        out.force[I] = f.E * fl[I];
        out.moment[I] = f.E * ml;
    }
    out.bad = !std::isfinite(out.strain_energy) || !std::isfinite(out.hourglass_energy);
}

void internal_force(const Constants& c, const std::array<Vec3, 4>& x_old, const std::array<Vec3, 4>& x_new,
                    const std::array<Vec3, 4>& dtheta, State& st, Result& out) {
    std::array<Vec3, 4> mid, du;
    for (int I = 0; I < 4; ++I) {
        mid[I] = 0.5 * (x_old[I] + x_new[I]);
        du[I] = x_new[I] - x_old[I];
    }
    const Frame fm = make_frame(mid);
    const Frame fe = make_frame(x_new);
    if (!(fm.area > 0.0) || !(fe.area > 0.0)) {
        out.bad = true;
        return;
    }
    update_state(c, fm, du, dtheta, st);
    forces(c, fe, st, out);
}

Eigen::Matrix<double, 24, 24> linear_stiffness(const Constants& c, const std::array<Vec3, 4>& X) {
    const Frame f = make_frame(X);
    if (!(f.area > 0.0)) throw InputError("shell element: degenerate element (zero area)");
    Eigen::Matrix<double, 24, 24> K;
    for (int j = 0; j < 24; ++j) {
        std::array<Vec3, 4> du, dth;
        for (int I = 0; I < 4; ++I) du[I] = dth[I] = Vec3::Zero();
        (j % 6 < 3 ? du : dth)[j / 6][j % 3] = 1.0;
        State st;
        update_state(c, f, du, dth, st);
        Result r;
        forces(c, f, st, r);
        for (int I = 0; I < 4; ++I) {
            K.block<3, 1>(6 * I, j) = r.force[I];
            K.block<3, 1>(6 * I + 3, j) = r.moment[I];
        }
    }
    return K;
}

double critical_time_step(const ElasticMaterial& m, const std::array<Vec3, 4>& x, bool triangle) {
    if (triangle) {
        const std::array<Vec3, 3> t{x[0], x[1], x[2]};
        return cfl::time_step(cfl::triangle_shell_length(t), plate_wave_speed(m));
    }
    return cfl::time_step(cfl::quad_shell_length(x), plate_wave_speed(m));
}

double rotational_inertia(const Constants& c, const Frame& f, double m, double table_dt, bool triangle) {
    // Distinct nodes: a triangle's repeated node 3 joins node 2 (its B and gamma summed); a node's
    // share of the rotation in the transverse shear: 1/4 (one point), about 1/3 in a triangle's
    // edge-based shear (the kernel test checks the resulting bound with the exact stiffness).
    const int n = triangle ? 3 : 4;
    double b1[4], b2[4], gm[4], share[4];
    for (int a = 0; a < 4; ++a) {
        b1[a] = f.b1[a];
        b2[a] = f.b2[a];
        gm[a] = f.gamma[a];
        share[a] = 0.25;
    }
    if (triangle) {
        b1[2] += b1[3];
        b2[2] += b2[3];
        gm[2] += gm[3];
        // The edge-based shear weighs the nodes' rotations about equally.
        share[0] = share[1] = share[2] = 1.0 / 3.0;
    }
    double sum_b = 0.0, sum_b1 = 0.0, sum_b2 = 0.0, sum_g = 0.0;
    for (int a = 0; a < n; ++a) {
        sum_b += std::abs(b1[a]) + std::abs(b2[a]);
        sum_b1 += std::abs(b1[a]);
        sum_b2 += std::abs(b2[a]);
        sum_g += std::abs(gm[a]);
    }
    const double A = f.area, t = c.t;
    const double D = c.c11 * t * t * t / 12.0;
    const double k_theta = c.r_theta * c.E * t * t * t * A / 192.0 * f.bb;
    const double w2 = 4.0 / (table_dt * table_dt);  // (2 / dt)^2 of Table 2-1
    double J = c.rho * t * t * t / 12.0 * A / n;      // physical rotary inertia (the floor)
    for (int a = 0; a < n; ++a) {
        // Row of a rotation of node a in the Gershgorin bound of M^-1/2 K M^-1/2:
        //   rotation-rotation entries / J:  shear A kappa G t share_a sum_b share_b (= share_a),
        //     bending <= A D (|b1_a| + |b2_a|) sum_b (|b1_b| + |b2_b|), hourglass k_theta |g_a| sum |g_b|
        //   rotation-translation entries / sqrt(J m): shear coupling A kappa G t share_a sum_b |b_b|
        // Requiring  p / J + q / sqrt(J m) <= w2  gives s = 1 / sqrt(J) from p s^2 + (q / sqrt(m)) s = w2.
        const double p = A * c.kappa_G * t * share[a] + A * D * (std::abs(b1[a]) + std::abs(b2[a])) * sum_b +
                         k_theta * std::abs(gm[a]) * sum_g;
        const double q = A * c.kappa_G * t * share[a] * std::max(sum_b1, sum_b2) / std::sqrt(m);
        const double s = (-q + std::sqrt(q * q + 4.0 * p * w2)) / (2.0 * p);
        J = std::max(J, 1.0 / (s * s));
    }
    if (c.r_d > 0.0) {
        // Drilling row: k_d against J, coupling k_d (|B_1| + |B_2|) / 2 per node against sqrt(J m);
        // each node of a triangle's repeated pair carries its own k_d.
        const double kd = c.r_d * c.G * t * A / 4.0 * (triangle ? 2.0 : 1.0);
        const double p = kd, q = kd * 0.5 * (sum_b1 + sum_b2) / std::sqrt(m);
        const double s = (-q + std::sqrt(q * q + 4.0 * p * w2)) / (2.0 * p);
        J = std::max(J, 1.0 / (s * s));
    }
    return J;
}

LumpedMass lumped_mass(const Constants& c, const std::array<Vec3, 4>& X, bool triangle) {
    const Frame f = make_frame(X);
    if (!(f.area > 0.0)) throw InputError("shell element: degenerate element (zero area)");
    LumpedMass out;
    const double m = c.rho * c.t * f.area / (triangle ? 3.0 : 4.0);
    ElasticMaterial mat{"", c.E, c.nu, c.rho};
    const double J = rotational_inertia(c, f, m, critical_time_step(mat, X, triangle), triangle);
    for (int a = 0; a < (triangle ? 3 : 4); ++a) {
        out.mass[a] = m;
        out.inertia[a] = J;
    }
    return out;
}

}  // namespace fem::shellbt
