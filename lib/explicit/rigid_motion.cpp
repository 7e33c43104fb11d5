#include "explicit/rigid_motion.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "core/error.hpp"

namespace fem {

namespace {
// outer o inner (rigid_motion.hpp).
RigidPose compose_poses(const RigidPose& o, const RigidPose& i) {
    RigidPose p;
    p.R = o.R * i.R;
    p.d = o.R * i.d + o.d;
    const Vec3 wi = o.R * i.omega;
    p.omega = o.omega + wi;
    p.v0 = o.v0 + o.R * i.v0 - wi.cross(o.d);
    return p;
}
}  // namespace

RigidMotion RigidMotion::rotation(const Vec3& point, const Vec3& axis, Curve omega) {
    if (!(axis.norm() > 0.0) || !point.allFinite() || !axis.allFinite())
        throw InputError("rigid rotation: the axis has zero length or a point is not finite");
    RigidMotion m;
    m.parts_.push_back({true, point, axis.normalized(), std::move(omega)});
    return m;
}

RigidMotion RigidMotion::translation(const Vec3& velocity, Curve scale) {
    if (!velocity.allFinite()) throw InputError("rigid translation: the velocity is not finite");
    RigidMotion m;
    m.parts_.push_back({false, Vec3::Zero(), velocity, std::move(scale)});
    return m;
}

RigidMotion RigidMotion::piecewise_translation(const std::vector<std::pair<double, Vec3>>& start_and_velocity,
                                               const std::string& name) {
    const auto& sv = start_and_velocity;
    if (sv.empty()) throw InputError(fmt::format("{}: no segments", name));
    for (std::size_t i = 0; i < sv.size(); ++i) {
        if (!std::isfinite(sv[i].first) || !sv[i].second.allFinite())
            throw InputError(fmt::format("{}: segment {} has a non-finite time or velocity", name, i));
        if (i > 0 && !(sv[i].first > sv[i - 1].first))
            throw InputError(fmt::format("{}: segment {} starts at {} s, not after segment {} ({} s)", name, i, sv[i].first,
                                         i - 1, sv[i - 1].first));
    }
    // Translations commute, so the order of the parts does not matter: x = X + sum_i v_i int_0^t s_i.
    RigidMotion m;
    for (std::size_t i = 0; i < sv.size(); ++i) {
        Curve scale = i + 1 < sv.size() ? Curve::pulse(sv[i].first, sv[i + 1].first) : Curve::step(sv[i].first);
        m.parts_.push_back({false, Vec3::Zero(), sv[i].second, std::move(scale)});
    }
    return m;
}

RigidMotion RigidMotion::then(const RigidMotion& outer) const {
    RigidMotion m = *this;
    m.parts_.insert(m.parts_.end(), outer.parts_.begin(), outer.parts_.end());
    return m;
}

RigidMotion compose(const RigidMotion& outer, const RigidMotion& inner) { return inner.then(outer); }

RigidPose RigidMotion::Elementary::pose(double t) const {
    RigidPose p;
    if (rotation) {
        p.R = Eigen::AngleAxisd(curve.integral(t), axis).toRotationMatrix();
        p.d = point - p.R * point;  // x = c + R (X - c)
        p.omega = curve(t) * axis;
        p.v0 = point.cross(p.omega);  // omega x (x - c) = v0 + omega x x
    } else {
        p.d = curve.integral(t) * axis;
        p.v0 = curve(t) * axis;
    }
    return p;
}

RigidPose RigidMotion::pose(double t) const {
    if (parts_.empty()) return {};
    RigidPose p = parts_[0].pose(t);
    for (std::size_t k = 1; k < parts_.size(); ++k) p = compose_poses(parts_[k].pose(t), p);
    return p;
}

}  // namespace fem
