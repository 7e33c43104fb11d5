#include "element/beam_corotational.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

#include <fmt/format.h>

#include "core/error.hpp"
#include "element/critical_time_step.hpp"
// The lane helpers; it also sets fp-contract=off for this whole file (no FMA: every version of the
// kernel gives the same bits).
#include "element/kernel_lanes.hpp"

namespace fem::beam {

Section Section::circular(double d) {
    const double r = 0.5 * d;
    Section s;
    s.area = std::numbers::pi * r * r;
    s.iy = s.iz = std::numbers::pi * r * r * r * r / 4.0;
    s.torsion = s.iy + s.iz;
    return s;
}

Section Section::rectangular(double b, double h) {
    Section s;
    s.area = b * h;
    s.iz = h * b * b * b / 12.0;
    s.iy = b * h * h * h / 12.0;
    const double a = std::max(b, h), c = std::min(b, h);
    s.torsion = a * c * c * c * (1.0 / 3.0 - 0.21 * c / a * (1.0 - std::pow(c / a, 4) / 12.0));  // Roark
    return s;
}

void Section::validate(const char* name) const {
    if (!(area > 0) || !(iy > 0) || !(iz > 0) || !(torsion > 0))
        throw InputError(fmt::format("beam section of {}: area {:.3g}, Iy {:.3g}, Iz {:.3g}, J {:.3g} must all be "
                                     "positive",
                                     name, area, iy, iz, torsion));
}

Reference make_reference(const Vec3& a, const Vec3& b, const Vec3& orientation) {
    Reference r;
    const Vec3 d = b - a;
    r.length = d.norm();
    if (!(r.length > 0.0)) throw InputError("beam element of zero length");
    const Vec3 e1 = d / r.length;
    Vec3 t = orientation;
    if (t.squaredNorm() == 0.0 || t.cross(e1).norm() < 1e-8 * t.norm()) {
        int k = 0;
        e1.cwiseAbs().minCoeff(&k);
        t = Vec3::Unit(k);
    }
    const Vec3 e2 = (t - t.dot(e1) * e1).normalized();
    r.frame0.col(0) = e1;
    r.frame0.col(1) = e2;
    r.frame0.col(2) = e1.cross(e2);
    return r;
}

namespace {
// Rotation vector of a rotation matrix (the inverse of Rodrigues' formula). The local rotations of a
// corotational element are small, so the skew part w gives sin(angle) axis directly: the series
// below; the general formula (asin, or the acos of the trace above ~0.5 rad) otherwise.
template <class T>
[[gnu::always_inline]] inline void skew_part(const T (&A)[3][3], T (&w)[3], T& s2, T& c) {
    w[0] = 0.5 * (A[2][1] - A[1][2]);
    w[1] = 0.5 * (A[0][2] - A[2][0]);
    w[2] = 0.5 * (A[1][0] - A[0][1]);
    s2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];  // sin^2(angle)
    c = 0.5 * (A[0][0] + A[1][1] + A[2][2] - 1.0);   // cos(angle)
}
// angle / sin(angle) = 1 + s^2/6 + 3 s^4/40 + 5 s^6/112 + ...: the series to s^4 is exact to 1e-14
// below s = 0.005, the usual size of a local rotation.
template <class T>
[[gnu::always_inline]] inline T small_rotation_factor(const T& s2) { return 1.0 + s2 * (1.0 / 6.0 + s2 * (3.0 / 40.0)); }
inline bool small_rotation(double s2, double c) { return c > 0.85 && s2 < 2.5e-5; }

// The general formula, for one element (matrix entries A[i][j]).
[[gnu::noinline]] void log_rotation_general(const double (&A)[3][3], double (&th)[3]) {
    double w[3], s2, c;
    skew_part(A, w, s2, c);
    if (c > 0.85) {
        const double s = std::sqrt(s2);
        const double f = std::asin(std::min(s, 1.0)) / s;
        for (int i = 0; i < 3; ++i) th[i] = f * w[i];
        return;
    }
    Mat3 R;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) R(i, j) = A[i][j];
    const Eigen::AngleAxisd aa(R);
    for (int i = 0; i < 3; ++i) th[i] = aa.angle() * aa.axis()[i];
}

inline void log_rotation(const double (&A)[3][3], double (&th)[3]) {
    double w[3], s2, c;
    skew_part(A, w, s2, c);
    if (!small_rotation(s2, c)) return log_rotation_general(A, th);
    const double f = small_rotation_factor(s2);
    for (int i = 0; i < 3; ++i) th[i] = f * w[i];
}
inline void log_rotation(const hex8::Lanes (&A)[3][3], hex8::Lanes (&th)[3]) {
    hex8::Lanes w[3], s2, c;
    skew_part(A, w, s2, c);
    const hex8::Lanes f = small_rotation_factor(s2);
    for (int i = 0; i < 3; ++i) th[i] = f * w[i];
    for (int l = 0; l < hex8::kLanes; ++l)
        if (!small_rotation(s2[l], c[l])) {  // this lane alone, as the one-element path does
            double a[3][3], t[3];
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) a[i][j] = A[i][j][l];
            log_rotation_general(a, t);
            for (int i = 0; i < 3; ++i) th[i][l] = t[i];
        }
}

template <class T>
[[gnu::always_inline]] inline T abs_lanes(const T& x) { return lanes::select(x < 0.0, -x, x); }
template <class T>
[[gnu::always_inline]] inline T max_lanes(const T& a, const T& b) { return lanes::select(b > a, b, a); }

// The corotational element (header): frame E from the chord and the mean of the nodal triads' second
// axes, local rotations th_n = log(E^T R_n E0), linear Euler-Bernoulli resultants, rotated back.
template <class T>
[[gnu::always_inline]] inline void kernel(const PackedT<T>& p, const T (&x1)[3], const T (&x2)[3], const T (&R1)[3][3],
                                          const T (&R2)[3][3], KernelResultT<T>& out) {
    const T d[3] = {x2[0] - x1[0], x2[1] - x1[1], x2[2] - x1[2]};
    const T l = lanes::sqrt_lanes(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    T E[3][3];  // columns e1, e2, e3
    for (int i = 0; i < 3; ++i) E[i][0] = d[i] / l;
    // Nodal triads T_n = R_n E0.
    T T1[3][3], T2[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            T1[i][j] = R1[i][0] * p.frame0[0][j] + R1[i][1] * p.frame0[1][j] + R1[i][2] * p.frame0[2][j];
            T2[i][j] = R2[i][0] * p.frame0[0][j] + R2[i][1] * p.frame0[1][j] + R2[i][2] * p.frame0[2][j];
        }
    {
        T t[3];
        for (int i = 0; i < 3; ++i) t[i] = 0.5 * (T1[i][1] + T2[i][1]);
        const T te = t[0] * E[0][0] + t[1] * E[1][0] + t[2] * E[2][0];
        for (int i = 0; i < 3; ++i) t[i] = t[i] - te * E[i][0];
        const T tn = lanes::sqrt_lanes(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
        for (int i = 0; i < 3; ++i) E[i][1] = t[i] / tn;
    }
    E[0][2] = E[1][0] * E[2][1] - E[2][0] * E[1][1];
    E[1][2] = E[2][0] * E[0][1] - E[0][0] * E[2][1];
    E[2][2] = E[0][0] * E[1][1] - E[1][0] * E[0][1];
    // Local rotations from A_n = E^T T_n.
    T th1[3], th2[3];
    {
        T A1[3][3], A2[3][3];
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) {
                A1[r][c] = E[0][r] * T1[0][c] + E[1][r] * T1[1][c] + E[2][r] * T1[2][c];
                A2[r][c] = E[0][r] * T2[0][c] + E[1][r] * T2[1][c] + E[2][r] * T2[2][c];
            }
        log_rotation(A1, th1);
        log_rotation(A2, th2);
    }

    const T N = p.axial * (l - p.length);
    const T Tq = p.torsion * (th2[0] - th1[0]);
    const T Mz1 = p.bend_z * (4.0 * th1[2] + 2.0 * th2[2]), Mz2 = p.bend_z * (2.0 * th1[2] + 4.0 * th2[2]);
    const T My1 = p.bend_y * (4.0 * th1[1] + 2.0 * th2[1]), My2 = p.bend_y * (2.0 * th1[1] + 4.0 * th2[1]);
    // Shears from moment equilibrium over the current length (virtual work with the chord rotation).
    const T inv_l = 1.0 / l;
    const T Vy = (Mz1 + Mz2) * inv_l;   // on node 1 along +e2 (node 2 gets -Vy)
    const T Vz = -(My1 + My2) * inv_l;  // on node 1 along +e3
    const T mN = -N, mT = -Tq;
    for (int i = 0; i < 3; ++i) {
        out.force[i] = E[i][0] * mN + E[i][1] * Vy + E[i][2] * Vz;
        out.moment[0][i] = E[i][0] * mT + E[i][1] * My1 + E[i][2] * Mz1;
        out.moment[1][i] = E[i][0] * Tq + E[i][1] * My2 + E[i][2] * Mz2;
    }
    out.length = l;
    out.axial_force = N;
    out.strain_energy = 0.5 * N * (l - p.length) + 0.5 * Tq * (th2[0] - th1[0]) +
                        p.bend_z * (2.0 * th1[2] * th1[2] + 2.0 * th1[2] * th2[2] + 2.0 * th2[2] * th2[2]) +
                        p.bend_y * (2.0 * th1[1] * th1[1] + 2.0 * th1[1] * th2[1] + 2.0 * th2[1] * th2[1]);
    out.max_stress = abs_lanes(N) * p.inv_area + max_lanes(abs_lanes(Mz1), abs_lanes(Mz2)) * p.fibre_z +
                     max_lanes(abs_lanes(My1), abs_lanes(My2)) * p.fibre_y;
}
}  // namespace

Stiffness Stiffness::of(const Reference& ref, const Section& s, const ElasticMaterial& m) {
    Stiffness k;
    const double L0 = ref.length, E = m.youngs_modulus;
    k.length = L0;
    k.axial = E * s.area / L0;
    k.torsion = m.shear_modulus() * s.torsion / L0;
    k.bend_y = E * s.iy / L0;
    k.bend_z = E * s.iz / L0;
    // Outer-fibre stress for output: the distance of the outer fibre from I and A of a solid section
    // (c = sqrt(3 I / A) for a rectangle's side, 2 sqrt(I/A) for a circle: use the larger, conservative).
    k.inv_area = 1.0 / s.area;
    k.fibre_y = 2.0 * std::sqrt(s.iy / s.area) / s.iy;
    k.fibre_z = 2.0 * std::sqrt(s.iz / s.area) / s.iz;
    return k;
}

Packed pack(const Reference& ref, const Stiffness& k) {
    Packed p;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) p.frame0[i][j] = ref.frame0(i, j);
    p.length = k.length;
    p.axial = k.axial;
    p.torsion = k.torsion;
    p.bend_y = k.bend_y;
    p.bend_z = k.bend_z;
    p.inv_area = k.inv_area;
    p.fibre_y = k.fibre_y;
    p.fibre_z = k.fibre_z;
    return p;
}

void pack_lane(const Packed& p, int l, PackedBlock& b) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) b.frame0[i][j][l] = p.frame0[i][j];
    b.length[l] = p.length;
    b.axial[l] = p.axial;
    b.torsion[l] = p.torsion;
    b.bend_y[l] = p.bend_y;
    b.bend_z[l] = p.bend_z;
    b.inv_area[l] = p.inv_area;
    b.fibre_y[l] = p.fibre_y;
    b.fibre_z[l] = p.fibre_z;
}

void internal_force(const Packed& p, const double (&x1)[3], const double (&x2)[3], const double (&R1)[3][3],
                    const double (&R2)[3][3], KernelResult& out) {
    kernel(p, x1, x2, R1, R2, out);
}

FEM_KERNEL_CLONES
void internal_force(const PackedBlock& p, const hex8::Lanes (&x1)[3], const hex8::Lanes (&x2)[3],
                    const hex8::Lanes (&R1)[3][3], const hex8::Lanes (&R2)[3][3], KernelResultBlock& out) {
    kernel(p, x1, x2, R1, R2, out);
}

void internal_force(const Reference& ref, const Section& s, const ElasticMaterial& m, const Vec3& x1,
                    const Vec3& x2, const Mat3& R1, const Mat3& R2, Result& out) {
    internal_force(ref, Stiffness::of(ref, s, m), x1, x2, R1, R2, out);
}

void internal_force(const Reference& ref, const Stiffness& k, const Vec3& x1, const Vec3& x2, const Mat3& R1,
                    const Mat3& R2, Result& out) {
    double a[3], b[3], Ra[3][3], Rb[3][3];
    for (int i = 0; i < 3; ++i) {
        a[i] = x1[i];
        b[i] = x2[i];
        for (int j = 0; j < 3; ++j) {
            Ra[i][j] = R1(i, j);
            Rb[i][j] = R2(i, j);
        }
    }
    KernelResult r;
    internal_force(pack(ref, k), a, b, Ra, Rb, r);
    out.force[0] = Vec3(r.force[0], r.force[1], r.force[2]);
    out.force[1] = -out.force[0];
    out.moment[0] = Vec3(r.moment[0][0], r.moment[0][1], r.moment[0][2]);
    out.moment[1] = Vec3(r.moment[1][0], r.moment[1][1], r.moment[1][2]);
    out.length = r.length;
    out.axial_force = r.axial_force;
    out.strain_energy = r.strain_energy;
    out.max_stress = r.max_stress;
}

void rotate(const Vec3& phi, Mat3& R) {
    const double t2 = phi.squaredNorm();
    if (!(t2 > 0.0)) return;
    double a, b;  // sin t / t and (1 - cos t) / t^2
    if (t2 < 1e-4) {
        // Series to t^6 (the next terms, t^8 / 9! and t^8 / 10!, are below 1e-21 here).
        a = 1.0 - t2 * (1.0 / 6.0) * (1.0 - t2 * (1.0 / 20.0) * (1.0 - t2 * (1.0 / 42.0)));
        b = 0.5 * (1.0 - t2 * (1.0 / 12.0) * (1.0 - t2 * (1.0 / 30.0) * (1.0 - t2 * (1.0 / 56.0))));
    } else {
        const double t = std::sqrt(t2);
        a = std::sin(t) / t;
        b = (1.0 - std::cos(t)) / t2;
    }
    const double p0 = phi[0], p1 = phi[1], p2 = phi[2];
    double* r = R.data();  // column-major: column j at r[3 j]
    for (int j = 0; j < 3; ++j, r += 3) {  // each column c of R: c + a phi x c + b phi x (phi x c)
        const double c0 = r[0], c1 = r[1], c2 = r[2];
        const double q0 = p1 * c2 - p2 * c1, q1 = p2 * c0 - p0 * c2, q2 = p0 * c1 - p1 * c0;
        const double s0 = p1 * q2 - p2 * q1, s1 = p2 * q0 - p0 * q2, s2 = p0 * q1 - p1 * q0;
        r[0] = c0 + a * q0 + b * s0;
        r[1] = c1 + a * q1 + b * s1;
        r[2] = c2 + a * q2 + b * s2;
    }
}

double physical_rotational_inertia(const Section& s, const ElasticMaterial& m, double L) {
    return m.density * std::max(s.iy + s.iz, s.torsion) * L / 2.0;
}

double nodal_rotational_inertia(const Section& s, const ElasticMaterial& m, double L) {
    // Element Gershgorin rows with lumped mass mt = rho A L/2 and rotational inertia Jr = mt kappa L^2,
    // r^2 = I/A, rho2 = r^2/L^2, s = 1/sqrt(kappa):
    //   axial row:       omega^2 <= 4 c^2 / L^2
    //   rotational row:  omega^2 <= c^2 r^2/L^4 (12 s^2 + 24 s)
    // Requiring rotational <= axial: rho2 (3 s^2 + 6 s) <= 1 -> s = -1 + sqrt(1 + 1/(3 rho2)).
    const double mt = m.density * s.area * L / 2.0;
    const double r2 = std::max(s.iy, s.iz) / s.area;
    const double rho2 = r2 / (L * L);
    const double sv = -1.0 + std::sqrt(1.0 + 1.0 / (3.0 * rho2));
    const double kappa = 1.0 / (sv * sv);
    // Torsion row: 2 G J / (L Jr) <= 4 c^2/L^2 -> Jr >= G J L / (2 E) * rho.
    const double torsion = m.shear_modulus() * s.torsion * L * m.density / (2.0 * m.youngs_modulus);
    return std::max({mt * kappa * L * L, torsion, physical_rotational_inertia(s, m, L)});
}

double critical_time_step(const Section& s, const ElasticMaterial& m, const Vec3& x1, const Vec3& x2) {
    const std::array<Vec3, 2> nodes{x1, x2};
    const double dt_axial = cfl::critical_time_step(ElementShape::Beam2, nodes, m);
    return std::min(dt_axial, transverse_time_step(s, m, (x2 - x1).norm(), nodal_rotational_inertia(s, m, (x2 - x1).norm())));
}

double transverse_time_step(const Section& s, const ElasticMaterial& m, double L, double Jr) {
    // Transverse row of the Gershgorin bound (relevant only for stubby elements).
    const double c2 = m.youngs_modulus / m.density;
    const double r2 = std::max(s.iy, s.iz) / s.area;
    const double mt = m.density * s.area * L / 2.0;
    const double sv = std::sqrt(mt * L * L / Jr);
    const double w2 = c2 * r2 / (L * L * L * L) * (48.0 + 24.0 * sv);
    return 2.0 / std::sqrt(w2);
}

}  // namespace fem::beam
