#include "contact/rigid.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fem::contact {

RigidMotion RigidMotion::rotation(const Vec3& point, const Vec3& axis, Curve omega) {
    if (!(axis.norm() > 0.0)) throw InputError("rigid rotation: the axis has zero length");
    RigidMotion m;
    m.c_ = point;
    m.axis_ = axis.normalized();
    m.omega_ = std::move(omega);
    return m;
}

RigidMotion RigidMotion::translation(const Vec3& direction, Curve speed) {
    RigidMotion m;
    m.with_translation(direction, std::move(speed));
    return m;
}

RigidMotion& RigidMotion::with_translation(const Vec3& direction, Curve speed) {
    if (!(direction.norm() > 0.0)) throw InputError("rigid translation: the direction has zero length");
    dir_ = direction.normalized();
    speed_ = std::move(speed);
    return *this;
}

Mat3 RigidMotion::rotation_matrix(double t) const { return Eigen::AngleAxisd(angle(t), axis_).toRotationMatrix(); }

Vec3 RigidMotion::position(const Vec3& X, double t) const { return c_ + translation_at(t) + rotation_matrix(t) * (X - c_); }

Vec3 RigidMotion::velocity(const Vec3& X, double t) const { return velocity_at(position(X, t), t); }

Vec3 RigidMotion::velocity_at(const Vec3& x, double t) const {
    return speed_(t) * dir_ + angular_velocity(t).cross(x - c_ - translation_at(t));
}

RigidSurface RigidSurface::from_part(const Mesh& mesh, std::string_view part, RigidMotion motion, double depth) {
    if (!(depth > 0.0)) throw InputError(fmt::format("rigid surface '{}': depth {} must be > 0", part, depth));
    // Any material: the stiffness is discarded (a rigid side takes the deformable side's k).
    const auto dummy = ElasticMaterial::make("rigid", 1.0, 0.0, 1.0);
    ContactSurface s = ContactSurface::from_part(mesh, part, dummy);
    RigidSurface r;
    std::map<int, int> local;
    for (int node : s.nodes) {
        local[node] = static_cast<int>(r.points.size());
        r.points.push_back(mesh.nodes[node]);
    }
    for (auto& seg : s.segments) {
        for (int i = 0; i < seg.count; ++i) seg.n[i] = local.at(seg.n[i]);
        seg.stiffness = std::numeric_limits<double>::infinity();
        seg.depth = depth;
        seg.volume = 0.0;
    }
    s.nodes.clear();
    s.node_stiffness.clear();
    s.rigid = true;
    r.surface = std::move(s);
    r.motion = std::move(motion);
    return r;
}

RigidSurface RigidSurface::plane(const Vec3& centre, const Vec3& u, const Vec3& v, int nu, int nv, double depth,
                                 RigidMotion motion) {
    if (nu < 1 || nv < 1 || !(u.cross(v).norm() > 0.0) || !(depth > 0.0))
        throw InputError("rigid plane: needs nu, nv >= 1, non-parallel u and v, depth > 0");
    RigidSurface r;
    r.surface.name = "rigid plane";
    r.surface.rigid = true;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i)
            r.points.push_back(centre + (double(i) / nu - 0.5) * u + (double(j) / nv - 0.5) * v);
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            Segment s;
            const int a = j * (nu + 1) + i;
            s.n = {a, a + 1, a + nu + 2, a + nu + 1};  // counter-clockwise about u x v
            s.depth = depth;
            s.area = segment_area(s, r.points);
            r.surface.segments.push_back(s);
        }
    r.motion = std::move(motion);
    return r;
}

void RigidSurface::state(double t, std::vector<Vec3>& x, std::vector<Vec3>& v) const {
    x.resize(points.size());
    v.resize(points.size());
    const Mat3 R = motion.rotation_matrix(t);
    const Vec3 c = motion.centre(), u = motion.translation_at(t);
    for (std::size_t i = 0; i < points.size(); ++i) {
        x[i] = c + u + R * (points[i] - c);
        v[i] = motion.velocity_at(x[i], t);
    }
}

}  // namespace fem::contact
