#pragma once
// Node-to-segment projection (thesis Sec 2.3.6): the closest point of a master segment to a slave
// node, the segment normal there and the signed gap g_n of Eq 2-29 (negative: penetration).
//
// Triangle: exact closest point (Voronoi regions of vertices, edges and face). Bilinear quad:
// Newton iteration on (xi, eta) for the stationary point of |x(xi, eta) - p|^2; when it does not
// converge inside [-1, 1]^2 the closest point of the four edges is taken (the minimum of a
// function on a square lies inside or on an edge).
#include <algorithm>
#include <array>
#include <cmath>

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

/// A box around a segment in a frame of its own, to tell cheaply that a node's projection onto the
/// segment cannot come out near it (ContactInterface::evaluate skips those projections). Centre c
/// (mean of the corners), unit normal n (triangle: its normal; quad: along the cross product of the
/// diagonals), in-plane unit axes e1, e2; half-extents w (warp, along n), a1, a2 of the corners. The
/// whole segment lies in the box: a triangle and a bilinear quad lie in the convex hull of their
/// corners, and the projection's closest point is a convex combination of them (its (xi, eta) are
/// in [-1, 1]^2).
/// Height bounds: the normal of the bilinear map, x_xi x x_eta, is affine in (xi, eta) (the xi eta
/// term is x_xieta x x_xieta = 0), so n . normal > 0 everywhere when it is at the four corners
/// (`normal_bounded`, asked with a margin: > 0.1 |corner normal|). Then for the closest point
/// (gap g, tangential offset t of project_*): height(p) = (point - c).n + g (normal.n) + (tangential
/// part).n, so  -w + min(g, 0) - t <= height(p) <= w + max(g, 0) + t.
struct SegmentBox {
    Vec3 c = Vec3::Zero(), n = Vec3::UnitZ(), e1 = Vec3::UnitX(), e2 = Vec3::UnitY();
    double w = 0.0, a1 = 0.0, a2 = 0.0;
    bool normal_bounded = false;
    /// (p - c) . n
    double height(const Vec3& p) const { return (p - c).dot(n); }
    /// A lower bound of the distance from p to every point of the segment (distance to the box).
    double distance_below(const Vec3& p) const {
        const Vec3 r = p - c;
        const double dn = std::max(0.0, std::abs(r.dot(n)) - w), d1 = std::max(0.0, std::abs(r.dot(e1)) - a1),
                     d2 = std::max(0.0, std::abs(r.dot(e2)) - a2);
        return std::sqrt(dn * dn + d1 * d1 + d2 * d2);
    }
};
SegmentBox segment_box(const Vec3& a, const Vec3& b, const Vec3& c);
SegmentBox segment_box(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

}  // namespace fem::contact
