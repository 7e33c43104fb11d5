#pragma once
// Node-to-segment projection (thesis Sec 2.3.6): the closest point of a master segment to a slave
// node, the segment normal there and the signed gap g_n of Eq 2-29 (negative: penetration).
//
// Triangle: exact closest point (Voronoi regions of vertices, edges and face). Bilinear quad:
// Newton iteration on (xi, eta) for the stationary point of |x(xi, eta) - p|^2; when it does not
// converge inside [-1, 1]^2 the closest point of the four edges is taken (the minimum of a
// function on a square lies inside or on an edge).
#include <array>

#include "core/types.hpp"

namespace fem::contact {

struct Projection {
    Vec3 point = Vec3::Zero();          // closest point on the segment
    Vec3 normal = Vec3::UnitZ();        // unit outward normal of the segment at that point
    double gap = 0.0;                   // (p - point) . normal (Eq 2-29: < 0 penetration)
    double distance = 0.0;              // |p - point|
    double tangential_offset = 0.0;     // |p - point - gap normal|: 0 when p projects inside
    std::array<double, 4> shape{0, 0, 0, 0};  // shape functions of the segment nodes at `point`
    double xi = 0.0, eta = 0.0;         // parametric coordinates (triangle: area coordinates of nodes 1, 2)
    bool inside = false;                // the closest point is interior (not clamped to an edge)
};

/// Closest point of the triangle (a, b, c) (outward normal (b - a) x (c - a)) to p.
Projection project_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);
/// Closest point of the bilinear quadrilateral (a, b, c, d) (counter-clockwise about the outward
/// normal) to p.
Projection project_quad(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

}  // namespace fem::contact
