#pragma once
// Rigid bodies with prescribed motion (thesis Sec 3.5: the drum turning at 20 rpm, the fixed
// elliptical object; the ground of the verification tests).
//
// RigidMotion: x(t) = c + u(t) + R(theta(t)) (X - c), a rotation by theta(t) = int_0^t omega dt about
// a fixed axis through the point c (carried along by the translation u(t)), with omega(t) and the
// translation speed s(t) piecewise linear in time (held constant outside their points), so theta
// and u are integrated exactly. Velocity: v = u'(t) + omega(t) a x (x - c - u(t)).
// The same map gives the prescribed positions and velocities of deformable nodes tied to a rigid
// body ("the finger root on the drum").
//
// RigidSurface: a ContactSurface whose segment nodes are its own reference points, moved as one
// rigid body. Forces on it are not applied anywhere: they are summed into the resultant force and
// moment (the reaction a force transducer would measure, thesis Fig 3-21).
#include <utility>
#include <vector>

#include "contact/surface.hpp"
#include "core/types.hpp"
#include "explicit/curve.hpp"

namespace fem::contact {

class RigidMotion {
public:
    RigidMotion() = default;  // fixed in space
    static RigidMotion fixed() { return {}; }
    /// Rotation about the axis through `point` along `axis` (normalised) at angular velocity
    /// omega(t) [rad/s] (right-hand rule about `axis`).
    static RigidMotion rotation(const Vec3& point, const Vec3& axis, Curve omega);
    /// Translation with velocity direction * speed(t) [m/s].
    static RigidMotion translation(const Vec3& direction, Curve speed);
    /// Adds a translation to a rotation (the axis moves with it).
    RigidMotion& with_translation(const Vec3& direction, Curve speed);

    double angle(double t) const { return omega_.integral(t); }
    Vec3 angular_velocity(double t) const { return omega_(t) * axis_; }
    Vec3 translation_at(double t) const { return speed_.integral(t) * dir_; }
    Mat3 rotation_matrix(double t) const;
    /// Current position of the material point with reference position X.
    Vec3 position(const Vec3& X, double t) const;
    /// Velocity of the material point with reference position X at time t.
    Vec3 velocity(const Vec3& X, double t) const;
    /// Velocity of the body's point that is at the current position x at time t.
    Vec3 velocity_at(const Vec3& x, double t) const;
    const Vec3& centre() const { return c_; }

private:
    Vec3 c_ = Vec3::Zero(), axis_ = Vec3::UnitZ(), dir_ = Vec3::Zero();
    Curve omega_ = Curve::constant(0.0), speed_ = Curve::constant(0.0);
};

struct RigidSurface {
    ContactSurface surface;          // segments index `points`; surface.rigid = true
    std::vector<Vec3> points;        // reference positions
    RigidMotion motion;

    /// The outer surface of part `part` of `mesh` (solid or shell blocks), frozen as a rigid body;
    /// `depth` is the deepest penetration taken as contact (a fraction of the body's thickness).
    static RigidSurface from_part(const Mesh& mesh, std::string_view part, RigidMotion motion, double depth);
    /// A flat rectangle centred at `centre`, spanned by u and v (full lengths |u|, |v|), normal
    /// u x v / |u x v| (the side that contact pushes towards), split into nu x nv quads.
    static RigidSurface plane(const Vec3& centre, const Vec3& u, const Vec3& v, int nu, int nv, double depth,
                              RigidMotion motion = {});
    /// Positions and velocities of the points at time t.
    void state(double t, std::vector<Vec3>& x, std::vector<Vec3>& v) const;
};

}  // namespace fem::contact
