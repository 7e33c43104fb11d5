#include "element/beam_corotational.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

#include <fmt/format.h>

#include "core/error.hpp"
#include "element/critical_time_step.hpp"

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
// corotational element are small, so the skew part gives sin(angle) axis directly; the general
// formula (acos of the trace) takes over above ~0.5 rad.
Vec3 log_rotation(const Mat3& R) {
    const Vec3 w(0.5 * (R(2, 1) - R(1, 2)), 0.5 * (R(0, 2) - R(2, 0)), 0.5 * (R(1, 0) - R(0, 1)));
    const double s = w.norm();  // sin(angle)
    const double c = 0.5 * (R.trace() - 1.0);
    if (c > 0.85) {
        // angle / sin(angle) = 1 + s^2/6 + 3 s^4/40 + 5 s^6/112 + ...: the series to s^4 is exact to
        // 1e-14 below s = 0.005, the usual size of a local rotation; asin above.
        if (s < 5e-3) return (1.0 + s * s * (1.0 / 6.0 + s * s * (3.0 / 40.0))) * w;
        return (std::asin(std::min(s, 1.0)) / s) * w;
    }
    const Eigen::AngleAxisd aa(R);
    return aa.angle() * aa.axis();
}
}  // namespace

void internal_force(const Reference& ref, const Section& s, const ElasticMaterial& m, const Vec3& x1,
                    const Vec3& x2, const Mat3& R1, const Mat3& R2, Result& out) {
    const double L0 = ref.length;
    const Vec3 d = x2 - x1;
    const double l = d.norm();
    const Vec3 e1 = d / l;
    const Mat3 T1 = R1 * ref.frame0, T2 = R2 * ref.frame0;
    const Vec3 t = 0.5 * (T1.col(1) + T2.col(1));
    const Vec3 e2 = (t - t.dot(e1) * e1).normalized();
    Mat3 E;
    E.col(0) = e1;
    E.col(1) = e2;
    E.col(2) = e1.cross(e2);
    const Vec3 th1 = log_rotation(E.transpose() * T1);
    const Vec3 th2 = log_rotation(E.transpose() * T2);

    const double E_ = m.youngs_modulus, G = m.shear_modulus();
    const double N = E_ * s.area * (l - L0) / L0;
    const double T = G * s.torsion * (th2.x() - th1.x()) / L0;
    const double kz = E_ * s.iz / L0, ky = E_ * s.iy / L0;
    const double Mz1 = kz * (4 * th1.z() + 2 * th2.z()), Mz2 = kz * (2 * th1.z() + 4 * th2.z());
    const double My1 = ky * (4 * th1.y() + 2 * th2.y()), My2 = ky * (2 * th1.y() + 4 * th2.y());
    // Shears from moment equilibrium over the current length (virtual work with the chord rotation).
    const double Vy = (Mz1 + Mz2) / l;   // on node 1 along +e2 (node 2 gets -Vy)
    const double Vz = -(My1 + My2) / l;  // on node 1 along +e3
    const Vec3 f1(-N, Vy, Vz);
    const Vec3 m1(-T, My1, Mz1), m2(T, My2, Mz2);
    out.force[0] = E * f1;
    out.force[1] = -out.force[0];
    out.moment[0] = E * m1;
    out.moment[1] = E * m2;
    out.axial_force = N;
    out.strain_energy = 0.5 * N * (l - L0) + 0.5 * T * (th2.x() - th1.x()) +
                        kz * (2 * th1.z() * th1.z() + 2 * th1.z() * th2.z() + 2 * th2.z() * th2.z()) +
                        ky * (2 * th1.y() * th1.y() + 2 * th1.y() * th2.y() + 2 * th2.y() * th2.y());
    // Outer-fibre stress for output: the distance of the outer fibre from I and A of a solid section
    // (c = sqrt(3 I / A) for a rectangle's side, 2 sqrt(I/A) for a circle: use the larger, conservative).
    const double cz = 2.0 * std::sqrt(s.iz / s.area), cy = 2.0 * std::sqrt(s.iy / s.area);
    const double mb = std::max({std::abs(Mz1), std::abs(Mz2)}) * cz / s.iz +
                      std::max({std::abs(My1), std::abs(My2)}) * cy / s.iy;
    out.max_stress = std::abs(N) / s.area + mb;
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
