#pragma once
// Prescribed rigid-body motions (thesis Sec 3.5 and Ch 4: the drum turning at a scheduled speed, the
// conveyor pallet, the whole hand turned for the flip), for nodes tied to a rigid body
// (ExplicitModel::prescribe_motion) and for rigid parts (ExplicitModel::add_rigid_part).
//
// A RigidMotion maps a reference point X to x(t) = R(t) X + d(t). Elementary motions:
//   rotation(c, a, omega):  about the axis through c along a (right-hand rule), by the angle
//                           theta(t) = int_0^t omega (Curve::integral: exact for the piecewise-linear
//                           schedule), x = c + R(theta a) (X - c);
//   translation(v, s):      by v int_0^t s, i.e. at the velocity v s(t);
// and their composition: compose(outer, inner) (or inner.then(outer)) is x(t) = outer(t)(inner(t)(X)):
// the inner motion is described in the reference frame and carried along by the outer one. The flip
// of thesis Sec 4.4, "the drum spins about its own axis, stopped at 180 degrees, then the whole hand
// turns 135 degrees about the global z axis":
//
//   const double w = 2.095, t_stop = std::numbers::pi / w;       // the drum stops after half a turn
//   RigidMotion drum = RigidMotion::rotation(drum_centre, drum_axis, Curve::steps({{0, w}, {t_stop, 0}}));
//   RigidMotion flip = RigidMotion::rotation(Vec3::Zero(), Vec3::UnitZ(),
//                                            Curve::steps({{0, 0}, {1.5, 4.71}, {2.0, 0}}));
//   RigidMotion hand = compose(flip, drum);                      // flip(t) o drum(t)
//
// Velocities are analytic (not differences of positions): the spatial twist (omega, v0), so the
// velocity of the body point that is at x is v0 + omega x x. For the composition, with outer pose
// (R_o, d_o): R = R_o R_i, d = R_o d_i + d_o, omega = omega_o + R_o omega_i,
// v0 = v0_o + R_o v0_i - (R_o omega_i) x d_o.
#include <string>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "explicit/curve.hpp"

namespace fem {

/// Where a rigid motion has put the body at one time: x = R X + d, velocities v(x) = v0 + omega x x.
struct RigidPose {
    Mat3 R = Mat3::Identity();
    Vec3 d = Vec3::Zero();
    Vec3 omega = Vec3::Zero();  // spatial angular velocity [rad/s]
    Vec3 v0 = Vec3::Zero();     // velocity of the body point at the spatial origin [m/s]
    Vec3 position(const Vec3& X) const { return R * X + d; }
    /// Velocity of the body point that is at the current position x.
    Vec3 velocity_at(const Vec3& x) const { return v0 + omega.cross(x); }
    /// Velocity of the material point with reference position X.
    Vec3 velocity(const Vec3& X) const { return velocity_at(position(X)); }
};

class RigidMotion {
public:
    RigidMotion() = default;  // at rest: x = X
    static RigidMotion fixed() { return {}; }
    /// Rotation about the axis through `point` along `axis` (normalised; right-hand rule) at the
    /// angular speed omega(t) [rad/s]. Throws InputError for a zero axis.
    static RigidMotion rotation(const Vec3& point, const Vec3& axis, Curve omega);
    /// Translation at the velocity `velocity` x scale(t) [m/s] (default scale: constant 1).
    static RigidMotion translation(const Vec3& velocity, Curve scale = {});
    /// Translation along a polyline at piecewise-constant velocity, written like Curve::steps:
    /// (t_i, v_i) means the velocity v_i from t_i until t_{i+1} (the last one held for ever); at rest
    /// before t_0; times strictly increasing. E.g. the perch of thesis Table 5-6 on the conveyor,
    /// inclined 5 degrees until the apex at 0.7 s, then declined 30 degrees:
    ///   piecewise_translation({{0.0, {-0.4723, 0.04132, 0}}, {0.7, {-0.4105, -0.23705, 0}}})
    /// One translation per segment with a Curve::pulse (Curve::step for the last) as its scale, so
    /// the position is exact (Curve::integral) and the velocity at a corner t_i is the later one.
    /// Throws InputError naming `name` for an empty list, times not increasing or a non-finite value.
    static RigidMotion piecewise_translation(const std::vector<std::pair<double, Vec3>>& start_and_velocity,
                                             const std::string& name = "piecewise translation");
    /// This motion, then `outer` applied to the result: x(t) = outer(t)(this(t)(X)).
    RigidMotion then(const RigidMotion& outer) const;

    RigidPose pose(double t) const;
    Vec3 position(const Vec3& X, double t) const { return pose(t).position(X); }
    Vec3 velocity(const Vec3& X, double t) const { return pose(t).velocity(X); }
    /// Velocity of the body point that is at the current position x at time t.
    Vec3 velocity_at(const Vec3& x, double t) const { return pose(t).velocity_at(x); }
    Vec3 angular_velocity(double t) const { return pose(t).omega; }
    bool is_fixed() const { return parts_.empty(); }

private:
    struct Elementary {
        bool rotation = false;
        Vec3 point = Vec3::Zero();  // rotation: a point on the axis
        Vec3 axis = Vec3::UnitZ();  // rotation: unit axis; translation: the velocity vector
        Curve curve;                // omega(t), or the velocity scale
        RigidPose pose(double t) const;
    };
    std::vector<Elementary> parts_;  // applied in order: parts_[0] innermost
};

/// outer(t) o inner(t): inner.then(outer).
RigidMotion compose(const RigidMotion& outer, const RigidMotion& inner);

}  // namespace fem
