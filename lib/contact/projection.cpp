#include "contact/projection.hpp"

#include <algorithm>
#include <cmath>

namespace fem::contact {

namespace {

void finish(Projection& r, const Vec3& p) {
    const Vec3 d = p - r.point;
    r.distance = d.norm();
    r.gap = d.dot(r.normal);
    r.tangential_offset = (d - r.gap * r.normal).norm();
}

// Closest point of segment [a, b] to p: parameter in [0, 1].
double closest_on_edge(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 e = b - a;
    const double L2 = e.squaredNorm();
    return L2 > 0 ? std::clamp((p - a).dot(e) / L2, 0.0, 1.0) : 0.0;
}

// Bilinear map of the quad at (xi, eta) and its tangents.
struct QuadEval {
    Vec3 x, dxi, deta;
    std::array<double, 4> N;
};
QuadEval eval_quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double xi, double eta) {
    QuadEval q;
    q.N = {0.25 * (1 - xi) * (1 - eta), 0.25 * (1 + xi) * (1 - eta), 0.25 * (1 + xi) * (1 + eta),
           0.25 * (1 - xi) * (1 + eta)};
    q.x = q.N[0] * a + q.N[1] * b + q.N[2] * c + q.N[3] * d;
    q.dxi = 0.25 * ((1 - eta) * (b - a) + (1 + eta) * (c - d));
    q.deta = 0.25 * ((1 - xi) * (d - a) + (1 + xi) * (c - b));
    return q;
}

}  // namespace

Projection project_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    // Barycentric closest point by Voronoi regions (standard construction, e.g. Ericson,
    // Real-Time Collision Detection, Sec 5.1.5).
    Projection r;
    const Vec3 n = (b - a).cross(c - a);
    r.normal = n.normalized();
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    double v = 0, w = 0;  // weights of b and c
    bool interior = false;
    if (d1 <= 0 && d2 <= 0) {  // vertex a
    } else {
        const Vec3 bp = p - b;
        const double d3 = ab.dot(bp), d4 = ac.dot(bp);
        const Vec3 cp = p - c;
        const double d5 = ab.dot(cp), d6 = ac.dot(cp);
        const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
        if (d3 >= 0 && d4 <= d3) {
            v = 1;  // vertex b
        } else if (d6 >= 0 && d5 <= d6) {
            w = 1;  // vertex c
        } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
            v = d1 / (d1 - d3);  // edge ab
        } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
            w = d2 / (d2 - d6);  // edge ac
        } else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
            w = (d4 - d3) / ((d4 - d3) + (d5 - d6));  // edge bc
            v = 1 - w;
        } else {
            const double denom = 1.0 / (va + vb + vc);
            v = vb * denom;
            w = vc * denom;
            interior = true;
        }
    }
    r.shape = {1 - v - w, v, w, 0.0};
    r.xi = v;
    r.eta = w;
    r.point = a + v * ab + w * ac;
    r.inside = interior;
    finish(r, p);
    return r;
}

Projection project_quad(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    // Newton on grad(1/2 |x - p|^2) = 0; x is bilinear, so x_xixi = x_etaeta = 0 and x_xieta is constant.
    const Vec3 x_xe = 0.25 * (a - b + c - d);
    double xi = 0, eta = 0;
    bool converged = false;
    for (int it = 0; it < 25; ++it) {
        const QuadEval q = eval_quad(a, b, c, d, xi, eta);
        const Vec3 r = q.x - p;
        const double g0 = q.dxi.dot(r), g1 = q.deta.dot(r);
        const double h00 = q.dxi.squaredNorm(), h11 = q.deta.squaredNorm();
        const double h01 = q.dxi.dot(q.deta) + x_xe.dot(r);
        const double det = h00 * h11 - h01 * h01;
        if (!(std::abs(det) > 1e-300)) break;
        const double dxi = -(h11 * g0 - h01 * g1) / det, deta = -(h00 * g1 - h01 * g0) / det;
        // Damp big steps so that an iterate far outside the element does not run away.
        const double step = std::max(std::abs(dxi), std::abs(deta));
        const double s = step > 1.0 ? 1.0 / step : 1.0;
        xi += s * dxi;
        eta += s * deta;
        if (std::abs(xi) > 3 || std::abs(eta) > 3) break;
        if (step < 1e-12) {
            converged = true;
            break;
        }
    }
    Projection best;
    best.distance = std::numeric_limits<double>::infinity();
    auto take = [&](double x0, double e0, bool inside) {
        const QuadEval q = eval_quad(a, b, c, d, x0, e0);
        const double dist = (p - q.x).norm();
        if (dist >= best.distance) return;
        best.point = q.x;
        best.normal = q.dxi.cross(q.deta).normalized();
        best.shape = q.N;
        best.xi = x0;
        best.eta = e0;
        best.inside = inside;
        best.distance = dist;
    };
    constexpr double tol = 1e-10;
    if (converged && std::abs(xi) <= 1 + tol && std::abs(eta) <= 1 + tol) {
        take(std::clamp(xi, -1.0, 1.0), std::clamp(eta, -1.0, 1.0), true);
    } else {
        // The minimum lies on the boundary: closest point of each straight edge.
        const Vec3* v[4] = {&a, &b, &c, &d};
        constexpr double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (int e = 0; e < 4; ++e) {
            const int f = (e + 1) % 4;
            const double s = closest_on_edge(p, *v[e], *v[f]);
            take(corner[e][0] + s * (corner[f][0] - corner[e][0]), corner[e][1] + s * (corner[f][1] - corner[e][1]),
                 false);
        }
    }
    finish(best, p);
    return best;
}

namespace {

// The frame and extents of SegmentBox for corners x[0..count), normal direction N (not normalized),
// in-plane direction E; corner_normals: the map's normal at each corner.
SegmentBox make_box(const Vec3* const* x, int count, const Vec3& N, const Vec3& E, const Vec3* corner_normals) {
    SegmentBox b;
    for (int k = 0; k < count; ++k) b.c += *x[k];
    b.c /= count;
    const double ln = N.norm();
    if (ln > 0.0) b.n = N / ln;
    Vec3 e = E - E.dot(b.n) * b.n;  // orthogonal to n (to rounding): the frame's distances are Euclidean
    if (!(e.norm() > 0.0)) e = b.n.unitOrthogonal();
    b.e1 = e.normalized();
    b.e2 = b.n.cross(b.e1);
    b.normal_bounded = ln > 0.0;
    for (int k = 0; k < count; ++k) {
        const Vec3 r = *x[k] - b.c;
        b.w = std::max(b.w, std::abs(r.dot(b.n)));
        b.a1 = std::max(b.a1, std::abs(r.dot(b.e1)));
        b.a2 = std::max(b.a2, std::abs(r.dot(b.e2)));
        const double l = corner_normals[k].norm();
        if (!(corner_normals[k].dot(b.n) > 0.1 * l)) b.normal_bounded = false;
    }
    return b;
}

}  // namespace

SegmentBox segment_box(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 N = (b - a).cross(c - a);
    const Vec3* x[3] = {&a, &b, &c};
    const Vec3 normals[3] = {N, N, N};
    return make_box(x, 3, N, b - a, normals);
}

SegmentBox segment_box(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const Vec3* x[4] = {&a, &b, &c, &d};
    // x_xi x x_eta at the corners (-1,-1), (1,-1), (1,1), (-1,1), up to a positive factor.
    const Vec3 normals[4] = {(b - a).cross(d - a), (b - a).cross(c - b), (c - d).cross(c - b), (c - d).cross(d - a)};
    return make_box(x, 4, (c - a).cross(d - b), c - a, normals);
}

}  // namespace fem::contact
