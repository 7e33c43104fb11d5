#include "mesh/finger.hpp"

#include <gmsh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.hpp"
#include "mesh/gmsh.hpp"

namespace fem::finger {
namespace {

constexpr double pi = std::numbers::pi;

void check_cylinder(const EllipticCylinder& g, const char* who) {
    if (!(g.a > 0.0) || !(g.b > 0.0) || !(g.length > 0.0) || !std::isfinite(g.a + g.b + g.length))
        throw InputError(std::string(who) + ": the elliptic cylinder needs positive finite semi-axes and length (a = " +
                         std::to_string(g.a) + " m, b = " + std::to_string(g.b) + " m, L = " + std::to_string(g.length) +
                         " m)");
}

// Arc length along the ellipse x = a cos t, y = b sin t, tabulated so that points can be placed at
// equal arc-length spacing. The trapezoidal rule on a smooth periodic integrand converges
// geometrically, so 4096 intervals give the perimeter to round-off.
class EllipseArc {
public:
    EllipseArc(double a, double b) : a_(a), b_(b), t_(kSteps + 1), s_(kSteps + 1) {
        auto speed = [&](double t) { return std::hypot(a * std::sin(t), b * std::cos(t)); };
        const double dt = 2.0 * pi / kSteps;
        s_[0] = 0.0;
        for (int i = 0; i <= kSteps; ++i) t_[i] = i * dt;
        for (int i = 1; i <= kSteps; ++i) s_[i] = s_[i - 1] + 0.5 * dt * (speed(t_[i - 1]) + speed(t_[i]));
    }
    double perimeter() const { return s_.back(); }
    double arc_at(double t) const { return interpolate(t_, s_, t); }
    // Parametric angle at arc position s (any real s; wrapped into one turn).
    double angle_at(double s) const {
        const double P = perimeter();
        double w = std::fmod(s, P);
        if (w < 0) w += P;
        return interpolate(s_, t_, w);
    }
    Vec2 point_at_arc(double s) const {
        const double t = angle_at(s);
        return {a_ * std::cos(t), b_ * std::sin(t)};
    }

private:
    static constexpr int kSteps = 4096;
    static double interpolate(const std::vector<double>& x, const std::vector<double>& y, double v) {
        auto it = std::upper_bound(x.begin(), x.end(), v);
        std::size_t i = std::clamp<std::size_t>(it - x.begin(), 1, x.size() - 1);
        const double f = (v - x[i - 1]) / (x[i] - x[i - 1]);
        return y[i - 1] + f * (y[i] - y[i - 1]);
    }
    double a_, b_;
    std::vector<double> t_, s_;
};

// A structured quadrilateral cross-section (counter-clockwise quads seen from +z).
struct Section {
    std::vector<Vec2> nodes;
    std::vector<std::array<int, 4>> quads;
};

double cross2(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }

double quad_area(const Section& s, const std::array<int, 4>& q) {
    double A = 0.0;
    for (int i = 0; i < 4; ++i) A += cross2(s.nodes[q[i]], s.nodes[q[(i + 1) % 4]]);
    return 0.5 * A;
}

void check_section(const HexCrossSection& c) {
    auto bad = [](const std::string& what) { throw InputError("hex finger cross-section: " + what); };
    if (c.nx < 1 || c.ny < 1) bad("the inner block needs nx >= 1 and ny >= 1 (got " + std::to_string(c.nx) + " x " + std::to_string(c.ny) + ")");
    if (c.nr < 0) bad("the number of ring layers nr must be >= 0 (got " + std::to_string(c.nr) + ")");
    if (!(c.inner_scale > 0.0 && c.inner_scale <= 1.0)) bad("inner_scale must lie in (0, 1] (got " + std::to_string(c.inner_scale) + ")");
    if (!(c.bulge >= 0.0 && c.bulge <= 1.0)) bad("bulge must lie in [0, 1] (got " + std::to_string(c.bulge) + ")");
    if (c.nr == 0 && (c.inner_scale != 1.0 || c.bulge != 1.0))
        bad("without ring layers (nr = 0) the block must reach the ellipse: inner_scale = bulge = 1");
    if (c.nr > 0 && c.inner_scale == 1.0) bad("with ring layers the inner block must lie inside the ellipse (inner_scale < 1)");
}

Section build_section(const EllipseArc& arc, const HexCrossSection& c) {
    const int nx = c.nx, ny = c.ny, M = 2 * (nx + ny);
    const double P = arc.perimeter(), step = P / M;
    // Boundary nodes, counter-clockwise from the block's lower-left corner; the bottom side is
    // centred on t = 270 deg so that the layout is symmetric about both axes (when corner_shift = 0).
    const double s0 = arc.arc_at(1.5 * pi) - 0.5 * nx * step + c.corner_shift * P;
    std::vector<Vec2> outer(M);
    for (int k = 0; k < M; ++k) outer[k] = arc.point_at_arc(s0 + k * step);
    // Inner-block boundary: a blend of the straight side between the (scaled) corners and the
    // scaled ellipse.
    const std::array<int, 5> corner = {0, nx, nx + ny, 2 * nx + ny, M};
    std::vector<Vec2> inner(M);
    for (int side = 0; side < 4; ++side) {
        const Vec2 c0 = c.inner_scale * outer[corner[side]], c1 = c.inner_scale * outer[corner[side + 1] % M];
        const int n = corner[side + 1] - corner[side];
        for (int m = 0; m < n; ++m) {
            const int k = corner[side] + m;
            const Vec2 straight = c0 + (static_cast<double>(m) / n) * (c1 - c0);
            inner[k] = c.bulge * c.inner_scale * outer[k] + (1.0 - c.bulge) * straight;
        }
    }
    if (c.nr == 0) inner = outer;  // the mapped block: its boundary is the ellipse itself

    Section s;
    // Inner block by transfinite (Coons) interpolation of its four sides.
    auto boundary_k = [&](int i, int j) {  // perimeter index of block boundary node (i, j)
        if (j == 0) return i;
        if (i == nx) return nx + j;
        if (j == ny) return nx + ny + (nx - i);
        return (2 * nx + ny + (ny - j)) % M;  // i == 0
    };
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            const double xi = static_cast<double>(i) / nx, eta = static_cast<double>(j) / ny;
            const Vec2 B = inner[boundary_k(i, 0)], T = inner[boundary_k(i, ny)];
            const Vec2 L = inner[boundary_k(0, j)], R = inner[boundary_k(nx, j)];
            const Vec2 B0 = inner[boundary_k(0, 0)], B1 = inner[boundary_k(nx, 0)];
            const Vec2 T0 = inner[boundary_k(0, ny)], T1 = inner[boundary_k(nx, ny)];
            Vec2 p = (1 - eta) * B + eta * T + (1 - xi) * L + xi * R -
                     ((1 - xi) * (1 - eta) * B0 + xi * (1 - eta) * B1 + (1 - xi) * eta * T0 + xi * eta * T1);
            if (i == 0 || j == 0 || i == nx || j == ny) p = inner[boundary_k(i, j)];  // exact on the sides
            s.nodes.push_back(p);
        }
    const int nb = (nx + 1) * (ny + 1);
    auto block_node = [&](int i, int j) { return j * (nx + 1) + i; };
    std::vector<int> ring0(M);  // block boundary node of each perimeter index
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i)
            if (i == 0 || j == 0 || i == nx || j == ny) ring0[boundary_k(i, j)] = block_node(i, j);
    for (int r = 1; r <= c.nr; ++r)
        for (int k = 0; k < M; ++k) s.nodes.push_back(inner[k] + (static_cast<double>(r) / c.nr) * (outer[k] - inner[k]));
    auto ring_node = [&](int r, int k) { return r == 0 ? ring0[k % M] : nb + (r - 1) * M + (k % M); };

    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
            s.quads.push_back({block_node(i, j), block_node(i + 1, j), block_node(i + 1, j + 1), block_node(i, j + 1)});
    for (int r = 0; r < c.nr; ++r)
        for (int k = 0; k < M; ++k) s.quads.push_back({ring_node(r, k), ring_node(r, k + 1), ring_node(r + 1, k + 1), ring_node(r + 1, k)});
    for (auto& q : s.quads)
        if (quad_area(s, q) < 0.0) std::swap(q[1], q[3]);  // counter-clockwise seen from +z
    return s;
}

double longest_side(const Section& s, const std::array<int, 4>& q) {
    double longest = 0.0;
    for (int i = 0; i < 4; ++i) longest = std::max(longest, (s.nodes[q[(i + 1) % 4]] - s.nodes[q[i]]).norm());
    return longest;
}

// Table 2-1's hexahedron length for a prism of this quad extruded by dz is min(dz, A / longest
// side); the quad's own part A / longest side is what the layout controls.
double quad_length(const Section& s, const std::array<int, 4>& q) { return quad_area(s, q) / longest_side(s, q); }

double quad_min_scaled_jacobian(const Section& s, const std::array<int, 4>& q) {
    double worst = 1.0;
    for (int i = 0; i < 4; ++i) {
        const Vec2 e1 = s.nodes[q[(i + 1) % 4]] - s.nodes[q[i]], e2 = s.nodes[q[(i + 3) % 4]] - s.nodes[q[i]];
        worst = std::min(worst, cross2(e1, e2) / (e1.norm() * e2.norm()));
    }
    return worst;
}

// Mesh generation through Gmsh: common options for the tetrahedral meshes.
void set_tet_options(const TetOptions& o, const char* who) {
    if (!(o.element_length > 0.0) || !std::isfinite(o.element_length))
        throw InputError(std::string(who) + ": element_length must be positive (got " + std::to_string(o.element_length) + " m)");
    if (o.order != 1 && o.order != 2)
        throw InputError(std::string(who) + ": order must be 1 (tet4) or 2 (tet10), got " + std::to_string(o.order));
    gmsh::option::setNumber("Mesh.MeshSizeMin", o.element_length);
    gmsh::option::setNumber("Mesh.MeshSizeMax", o.element_length);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 1);
    gmsh::option::setNumber("Mesh.Algorithm", 6);    // Frontal-Delaunay surfaces
    if (o.algorithm_3d != 1 && o.algorithm_3d != 10)
        throw InputError(std::string(who) + ": algorithm_3d must be 1 (Delaunay) or 10 (HXT), got " + std::to_string(o.algorithm_3d));
    gmsh::option::setNumber("Mesh.Algorithm3D", o.algorithm_3d);  // default 1: Delaunay
    // Gmsh's tetrahedron optimiser (elements below quality 0.3) removes most slivers: a sliver's tiny
    // altitude would set the time step (Table 2-1). Debian's Gmsh is built without Netgen.
    gmsh::option::setNumber("Mesh.Optimize", o.optimize ? 1 : 0);
    gmsh::option::setNumber("Mesh.SecondOrderLinear", 0);  // tet10 mid-edge nodes on the true surface
}

// Surfaces of the current (synchronized) model lying in the plane z = z0.
std::vector<int> surfaces_at_z(double z0, double extent) {
    gmsh::vectorpair found;
    const double eps = 1e-6 * extent;
    gmsh::model::getEntitiesInBoundingBox(-extent, -extent, z0 - eps, extent, extent, z0 + eps, found, 2);
    std::vector<int> tags;
    for (const auto& [d, t] : found) tags.push_back(t);
    return tags;
}

// Physical groups, mesh, conversion; shared by tet_finger and detailed_finger. `volumes` are the
// finger's volumes; tip_point (or -1) a geometry point at the tip centre, embedded in the tip face.
Mesh mesh_finger_model(const std::vector<int>& volumes, double length, double extent, int tip_point,
                       const TetOptions& o, const std::string& who) {
    const std::vector<int> root = surfaces_at_z(0.0, extent), tip = surfaces_at_z(length, extent);
    if (root.empty() || tip.empty()) throw SolverError(who + ": could not find the root or tip face of the geometry");
    if (tip_point >= 0 && tip.size() == 1) gmsh::model::mesh::embed(0, {tip_point}, 2, tip[0]);
    gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, volumes), o.part);
    gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, root), "root");
    gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, tip), "tip");
    try {
        gmsh::model::mesh::generate(3);
        if (o.match_mean_volume) {
            // "Average element length" (Table 3-2) read as the edge of the regular tetrahedron with
            // the mean element volume, V_reg = h^3 / (6 sqrt 2). Gmsh's tetrahedra come out ~15 %
            // larger than the size asked for, so the size is corrected once, in proportion.
            double volume = 0.0;
            for (int v : volumes) {
                double mass = 0.0;
                gmsh::model::occ::getMass(3, v, mass);
                volume += mass;
            }
            std::vector<int> types;
            std::vector<std::vector<std::size_t>> tags, nodes;
            gmsh::model::mesh::getElements(types, tags, nodes, 3, -1);
            std::size_t count = 0;
            for (const auto& t : tags) count += t.size();
            const double h_mean = std::cbrt(6.0 * std::sqrt(2.0) * volume / static_cast<double>(count));
            const double h = o.element_length * o.element_length / h_mean;
            gmsh::option::setNumber("Mesh.MeshSizeMin", h);
            gmsh::option::setNumber("Mesh.MeshSizeMax", h);
            gmsh::model::mesh::clear();
            gmsh::model::mesh::generate(3);
        }
        if (o.order == 2) gmsh::model::mesh::setOrder(2);
    } catch (const std::string& e) {
        throw SolverError(who + ": Gmsh failed to mesh the finger: " + e);
    }
    Mesh m = mesh_from_gmsh_model(who);
    // tip_center: the tip node nearest the axis (the embedded point when there is one).
    const auto& tips = m.node_set("tip");
    int best = tips.front();
    for (int n : tips)
        if (m.nodes[n].head<2>().norm() < m.nodes[best].head<2>().norm()) best = n;
    m.node_sets["tip_center"] = {best};
    return m;
}

// Element volume and quality helpers.
double det3(const Vec3& a, const Vec3& b, const Vec3& c) { return a.dot(b.cross(c)); }

double hex_volume(const std::vector<Vec3>& x) {
    // 2 x 2 x 2 Gauss integration of det J: exact for the trilinear hexahedron.
    static const double g = 1.0 / std::sqrt(3.0);
    static const int sgn[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                  {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    double V = 0.0;
    for (int p = 0; p < 8; ++p) {
        const double q[3] = {g * sgn[p][0], g * sgn[p][1], g * sgn[p][2]};
        Mat3 J = Mat3::Zero();
        for (int a = 0; a < 8; ++a) {
            const double s0 = sgn[a][0], s1 = sgn[a][1], s2 = sgn[a][2];
            const Vec3 dN(0.125 * s0 * (1 + s1 * q[1]) * (1 + s2 * q[2]), 0.125 * s1 * (1 + s0 * q[0]) * (1 + s2 * q[2]),
                          0.125 * s2 * (1 + s0 * q[0]) * (1 + s1 * q[1]));
            J += x[a] * dN.transpose();
        }
        V += J.determinant();
    }
    return V;
}

// det J of the 10-node tetrahedron at barycentric point (L1, L2, L3) (L0 = 1 - L1 - L2 - L3), Gmsh
// node order: corners 0-3, mid-edge 01, 12, 20, 03, 23, 13 (element_shape.hpp).
double tet10_det(const std::vector<Vec3>& x, double l1, double l2, double l3) {
    const double L[4] = {1.0 - l1 - l2 - l3, l1, l2, l3};
    static const Vec3 dL[4] = {Vec3(-1, -1, -1), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    static const int edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}};
    Mat3 J = Mat3::Zero();
    for (int a = 0; a < 4; ++a) J += x[a] * ((4.0 * L[a] - 1.0) * dL[a]).transpose();
    for (int e = 0; e < 6; ++e) {
        const int i = edge[e][0], j = edge[e][1];
        J += x[4 + e] * (4.0 * (L[j] * dL[i] + L[i] * dL[j])).transpose();
    }
    return J.determinant();
}

// Area of a (possibly warped) quadrilateral face: half the norm of the cross product of its
// diagonals (as in Table 2-1's shell length).
double face_area(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return 0.5 * (c - a).cross(d - b).norm(); }

// Table 2-1 characteristic lengths: hexahedron V / A_max, tetrahedron 3 V / A_max.
double hex_length(const std::vector<Vec3>& x, double volume) {
    static constexpr int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    double largest = 0.0;
    for (const auto& f : faces) largest = std::max(largest, face_area(x[f[0]], x[f[1]], x[f[2]], x[f[3]]));
    return volume / largest;
}
double tet_length(const std::vector<Vec3>& x) {
    const double volume = std::abs(det3(x[1] - x[0], x[2] - x[0], x[3] - x[0])) / 6.0;
    auto area = [&](int a, int b, int c) { return 0.5 * (x[b] - x[a]).cross(x[c] - x[a]).norm(); };
    return 3.0 * volume / std::max({area(0, 1, 2), area(0, 1, 3), area(0, 2, 3), area(1, 2, 3)});
}

double tet10_volume(const std::vector<Vec3>& x) {
    // Collapsed (Duffy) 3 x 3 x 3 Gauss-Legendre rule: xi = u, eta = (1-u) v, zeta = (1-u)(1-v) w,
    // exact for det J of the quadratic map (degree 3) times the collapse Jacobian.
    static const double gp[3] = {0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)};
    static const double gw[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
    double V = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) {
                const double u = gp[i], v = gp[j], w = gp[k];
                V += gw[i] * gw[j] * gw[k] * (1 - u) * (1 - u) * (1 - v) * tet10_det(x, u, (1 - u) * v, (1 - u) * (1 - v) * w);
            }
    return V;
}

}  // namespace

ElasticMaterial rubber(double youngs_modulus) {
    return ElasticMaterial::make("rubber (Table 3-1)", youngs_modulus, 0.49, 1000.0);
}

std::vector<double> table_3_1_lengths() { return {3.0 * units::inch, 4.5 * units::inch, 6.0 * units::inch, 8.0 * units::inch}; }

HexCrossSection mapped_cross_section(int n) {
    if (n < 1) throw InputError("mapped_cross_section needs n >= 1 (got " + std::to_string(n) + ")");
    return HexCrossSection{n, n, 0, 1.0, 1.0, 0.125};
}

HexCrossSection choose_hex_cross_section(const EllipticCylinder& g, double h) {
    // Every quad of the chosen layout has a corner scaled Jacobian (sine of its worst corner angle) of
    // at least 0.5, i.e. corner angles between 30 and 150 degrees.
    constexpr double kMinScaledJacobian = 0.5;
    // No side longer than 1.5 h: the ring's radial sides must not stretch to make room.
    constexpr double kMaxSide = 1.5;
    check_cylinder(g, "choose_hex_cross_section");
    if (!(h > 0.0) || !std::isfinite(h)) throw InputError("choose_hex_cross_section: element_length must be positive");
    const EllipseArc arc(g.a, g.b);
    const double area = pi * g.a * g.b, n0 = area / (h * h);
    HexCrossSection best{};
    double best_score = -1.0, best_count_error = 0.0;
    const int nx_max = static_cast<int>(std::ceil(2.0 * g.a / h)) + 2, ny_max = static_cast<int>(std::ceil(2.0 * g.b / h)) + 2;
    const int nr_max = static_cast<int>(std::ceil(std::min(g.a, g.b) / h)) + 2;
    for (int nx = 1; nx <= nx_max; ++nx)
        for (int ny = 1; ny <= ny_max; ++ny)
            for (int nr = 1; nr <= nr_max; ++nr) {
                const int count = nx * ny + 2 * (nx + ny) * nr;
                if (count < 0.8 * n0 || count > 1.25 * n0) continue;
                const double mean_size = std::sqrt(area / count);
                for (int si = 0; si <= 10; ++si)
                    for (int bi = 0; bi <= 3; ++bi) {
                        const HexCrossSection c{nx, ny, nr, 0.3 + 0.05 * si, 0.25 * bi, 0.0};
                        const Section s = build_section(arc, c);
                        double shortest = std::numeric_limits<double>::infinity();
                        for (const auto& q : s.quads) {
                            if (quad_min_scaled_jacobian(s, q) < kMinScaledJacobian || longest_side(s, q) > kMaxSide * h) {
                                shortest = -1.0;  // a badly shaped or overlong element: layout refused
                                break;
                            }
                            shortest = std::min(shortest, quad_length(s, q));
                        }
                        const double score = shortest / mean_size, count_error = std::abs(count - n0);
                        if (score > best_score + 1e-9 || (std::abs(score - best_score) <= 1e-9 && count_error < best_count_error)) {
                            best = c;
                            best_score = score;
                            best_count_error = count_error;
                        }
                    }
            }
    if (best_score <= 0.0)
        throw InputError("choose_hex_cross_section: no O-grid layout fits element length " + std::to_string(h) +
                         " m on this ellipse (is the element larger than the cross-section?)");
    return best;
}

Mesh hex_finger(const EllipticCylinder& g, const HexCrossSection& c, int layers, std::string part) {
    check_cylinder(g, "hex_finger");
    check_section(c);
    if (layers < 1) throw InputError("hex_finger needs at least one layer along the finger (got " + std::to_string(layers) + ")");
    const Section s = build_section(EllipseArc(g.a, g.b), c);
    const int nc = static_cast<int>(s.nodes.size());
    Mesh m;
    m.nodes.reserve(static_cast<std::size_t>(nc) * (layers + 1));
    for (int k = 0; k <= layers; ++k)
        for (const Vec2& p : s.nodes) m.add_node(Vec3(p.x(), p.y(), g.length * k / layers));
    ElementBlock block{std::move(part), ElementShape::Hex8, {}};
    block.connectivity.reserve(s.quads.size() * 8 * layers);
    for (int k = 0; k < layers; ++k)
        for (const auto& q : s.quads) {
            const int lo = k * nc, hi = (k + 1) * nc;
            const int e[8] = {lo + q[0], lo + q[1], lo + q[2], lo + q[3], hi + q[0], hi + q[1], hi + q[2], hi + q[3]};
            block.add(e);
        }
    m.blocks.push_back(std::move(block));
    auto& root = m.node_sets["root"];
    auto& tip = m.node_sets["tip"];
    int centre = 0;
    for (int i = 0; i < nc; ++i) {
        root.push_back(i);
        tip.push_back(layers * nc + i);
        if (s.nodes[i].norm() < s.nodes[centre].norm()) centre = i;
    }
    m.node_sets["tip_center"] = {layers * nc + centre};
    return m;
}

Mesh hex_finger(const EllipticCylinder& g, double element_length, std::string part) {
    const HexCrossSection c = choose_hex_cross_section(g, element_length);
    const int layers = std::max(1, static_cast<int>(std::lround(g.length / element_length)));
    return hex_finger(g, c, layers, std::move(part));
}

Mesh tet_finger(const EllipticCylinder& g, const TetOptions& o) {
    check_cylinder(g, "tet_finger");
    if (g.a < g.b) throw InputError("tet_finger: the major semi-axis a must lie along x (a >= b)");
    GmshSession session;
    gmsh::clear();
    try {
        gmsh::model::add("finger");
        set_tet_options(o, "tet_finger");
        const int disk = gmsh::model::occ::addDisk(0, 0, 0, g.a, g.b);
        gmsh::vectorpair out;
        gmsh::model::occ::extrude({{2, disk}}, 0, 0, g.length, out);
        int volume = -1;
        for (const auto& [d, t] : out)
            if (d == 3) volume = t;
        const int tip_point = gmsh::model::occ::addPoint(0, 0, g.length);
        gmsh::model::occ::synchronize();
        Mesh m = mesh_finger_model({volume}, g.length, 4.0 * (g.a + g.b + g.length), tip_point, o, "tet_finger");
        gmsh::clear();
        return m;
    } catch (const std::string& e) {  // the Gmsh API throws its error message
        gmsh::clear();
        throw SolverError("tet_finger: Gmsh failed: " + e);
    } catch (...) {
        gmsh::clear();
        throw;
    }
}

double detailed_finger_volume(const DetailedFinger& g) {
    const double a = g.body.a, b = g.body.b, s = g.root_scale, h = g.rib_height;
    const double A1 = pi * a * b, A0 = s * s * A1;
    double V = g.taper_length / 3.0 * (A0 + A1 + std::sqrt(A0 * A1));  // elliptic frustum
    V += A1 * (g.body.length - g.taper_length);
    V += g.rib_count * pi * ((a + h) * (b + h) - a * b) * g.rib_width;
    if (g.magnet_pocket) V -= pi * g.magnet_radius * g.magnet_radius * g.magnet_height;
    return V;
}

Mesh detailed_finger(const DetailedFinger& g, const TetOptions& o) {
    const auto& body = g.body;
    check_cylinder(body, "detailed_finger");
    auto bad = [](const std::string& what) { throw InputError("detailed_finger: " + what); };
    if (body.a < body.b) bad("the major semi-axis a must lie along x (a >= b)");
    if (!(g.root_scale >= 1.0)) bad("root_scale must be >= 1 (the root is the larger section), got " + std::to_string(g.root_scale));
    if (!(g.taper_length > 0.0 && g.taper_length < body.length)) bad("taper_length must lie in (0, length)");
    if (g.rib_count < 0) bad("rib_count must be >= 0");
    const double untapered = body.length - g.taper_length, pitch = untapered / (g.rib_count + 1);
    if (g.rib_count > 0 && (!(g.rib_height > 0.0) || !(g.rib_width > 0.0) || g.rib_width >= pitch))
        bad("ribs need positive height and a width below their pitch (" + std::to_string(pitch) + " m)");
    if (g.magnet_pocket && (!(g.magnet_radius > 0.0 && g.magnet_radius < body.b) || !(g.magnet_height > 0.0 && g.magnet_height < pitch)))
        bad("the magnet pocket must fit inside the tip");

    GmshSession session;
    gmsh::clear();
    try {
        gmsh::model::add("detailed_finger");
        set_tet_options(o, "detailed_finger");
        namespace occ = gmsh::model::occ;
        // Root taper: ruled loft between two similar ellipses.
        const int w0 = occ::addWire({occ::addEllipse(0, 0, 0, g.root_scale * body.a, g.root_scale * body.b)});
        const int w1 = occ::addWire({occ::addEllipse(0, 0, g.taper_length, body.a, body.b)});
        gmsh::vectorpair taper;
        occ::addThruSections({w0, w1}, taper, -1, true, true);
        // Body from the end of the taper to the tip, and the ribs.
        gmsh::vectorpair tools, out;
        occ::extrude({{2, occ::addDisk(0, 0, g.taper_length, body.a, body.b)}}, 0, 0, untapered, out);
        for (const auto& dt : out)
            if (dt.first == 3) tools.push_back(dt);
        for (int r = 0; r < g.rib_count; ++r) {
            const double z = g.taper_length + (r + 1) * pitch - 0.5 * g.rib_width;
            gmsh::vectorpair rib;
            occ::extrude({{2, occ::addDisk(0, 0, z, body.a + g.rib_height, body.b + g.rib_height)}}, 0, 0, g.rib_width, rib);
            for (const auto& dt : rib)
                if (dt.first == 3) tools.push_back(dt);
        }
        gmsh::vectorpair object;
        for (const auto& dt : taper)
            if (dt.first == 3) object.push_back(dt);
        gmsh::vectorpair fused;
        std::vector<gmsh::vectorpair> map;
        occ::fuse(object, tools, fused, map);
        if (g.magnet_pocket) {
            const int pocket = occ::addCylinder(0, 0, body.length - g.magnet_height, 0, 0, g.magnet_height, g.magnet_radius);
            gmsh::vectorpair cut;
            occ::cut(fused, {{3, pocket}}, cut, map);
            fused = cut;
        }
        const int tip_point = g.magnet_pocket ? -1 : occ::addPoint(0, 0, body.length);
        occ::synchronize();
        std::vector<int> volumes;
        for (const auto& [d, t] : fused)
            if (d == 3) volumes.push_back(t);
        if (volumes.size() != 1) throw SolverError("detailed_finger: the geometry did not fuse into one volume");
        const double extent = 4.0 * (g.root_scale * body.a + body.b + body.length);
        Mesh m = mesh_finger_model(volumes, body.length, extent, tip_point, o, "detailed_finger");
        gmsh::clear();
        return m;
    } catch (const std::string& e) {
        gmsh::clear();
        throw SolverError("detailed_finger: Gmsh failed to build the geometry: " + e);
    } catch (...) {
        gmsh::clear();
        throw;
    }
}

std::vector<ModelingCase> table_3_2_cases() {
    const double L = 4.5 * units::inch;  // "A 4.5-inch compliant finger is chosen for this study"
    const std::string tet_note =
        "'tetra element': the node/element counts of Table 3-2 (7481/4682, 36782/23147: 1.6 nodes per element) "
        "are those of 10-node tetrahedra, as is the SOLID92 model of Fig 3-2";
    return {
        {"A", "Simplified Model Hexa Element", ElementShape::Hex8, 4.0 * units::mm, false, L,
         "1080 nodes / 725 elements = 36 x 30 / 25 x 29: a 5 x 5 mapped cross-section, 29 layers"},
        {"B", "Simplified Model Refined Hexa Element", ElementShape::Hex8, 2.0 * units::mm, false, L,
         "5900 nodes / 4698 elements = 100 x 59 / 81 x 58: a 9 x 9 mapped cross-section, 58 layers"},
        {"C", "Simplified Model Tetra Element", ElementShape::Tet10, 4.0 * units::mm, false, L, tet_note},
        {"D", "Detailed Model Tetra Element", ElementShape::Tet10, 2.8 * units::mm, true, L,
         tet_note + "; the detailed geometry is reconstructed (DetailedFinger)"},
    };
}

Mesh mesh_case(const ModelingCase& c, std::string part) {
    const EllipticCylinder g{semi_major_axis, semi_minor_axis, c.finger_length};
    const int order = c.shape == ElementShape::Tet10 ? 2 : 1;
    if (c.shape == ElementShape::Hex8) return hex_finger(g, c.element_length, std::move(part));
    if (c.shape != ElementShape::Tet10 && c.shape != ElementShape::Tet4)
        throw InputError("mesh_case: case " + c.id + " asks for " + std::string(to_string(c.shape)) + " elements (hex8, tet4 or tet10)");
    const TetOptions o{c.element_length, order, std::move(part)};
    if (c.detailed) {
        DetailedFinger d;
        d.body = g;
        return detailed_finger(d, o);
    }
    return tet_finger(g, o);
}

MeshQuality mesh_quality(const Mesh& mesh) {
    MeshQuality q;
    q.min_characteristic_length = std::numeric_limits<double>::infinity();
    double edge_sum = 0.0;
    long edge_count = 0;
    q.min_edge = std::numeric_limits<double>::infinity();
    auto edges = [&](const std::vector<Vec3>& x, std::span<const std::array<int, 2>> list) {
        for (const auto& e : list) {
            const double l = (x[e[1]] - x[e[0]]).norm();
            q.min_edge = std::min(q.min_edge, l);
            q.max_edge = std::max(q.max_edge, l);
            edge_sum += l;
            ++edge_count;
        }
    };
    static const std::array<std::array<int, 2>, 12> hex_edges = {
        {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}}};
    static const std::array<std::array<int, 2>, 6> tet_edges = {{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}};
    // Corner neighbours of the hexahedron, ordered so that a right-handed corner gives det > 0.
    static const int hex_corner[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7}, {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
    static const int tet_corner[4][3] = {{1, 2, 3}, {2, 0, 3}, {0, 1, 3}, {1, 0, 2}};
    for (int b = 0; b < static_cast<int>(mesh.blocks.size()); ++b) {
        const auto& block = mesh.blocks[b];
        const ElementShape shape = block.shape;
        if (shape != ElementShape::Hex8 && shape != ElementShape::Tet4 && shape != ElementShape::Tet10) continue;
        for (int e = 0; e < block.size(); ++e) {
            const std::vector<Vec3> x = mesh.element_coordinates(b, e);
            double sj = 1.0, length = 0.0;
            ++q.solid_elements;
            if (shape == ElementShape::Hex8) {
                for (int i = 0; i < 8; ++i) {
                    const int* c = hex_corner[i];
                    const Vec3 u = x[c[0]] - x[i], v = x[c[1]] - x[i], w = x[c[2]] - x[i];
                    sj = std::min(sj, det3(u, v, w) / (u.norm() * v.norm() * w.norm()));
                }
                const double v = hex_volume(x);
                q.volume += v;
                length = hex_length(x, v);
                edges(x, hex_edges);
            } else {
                // Scaled Jacobian of the corner tetrahedron: sqrt(2) det / (product of the three
                // edge lengths at a corner), minimum over corners (1 for the regular tetrahedron).
                for (int i = 0; i < 4; ++i) {
                    const auto& c = tet_corner[i];
                    const Vec3 u = x[c[0]] - x[i], v = x[c[1]] - x[i], w = x[c[2]] - x[i];
                    const double s = std::sqrt(2.0) * det3(u, v, w) / (u.norm() * v.norm() * w.norm());
                    sj = std::min(sj, s);
                }
                const double v_lin = det3(x[1] - x[0], x[2] - x[0], x[3] - x[0]);
                length = tet_length(x);
                if (shape == ElementShape::Tet10) {
                    const double pts[5][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.25, 0.25, 0.25}};
                    for (const auto& p : pts) q.min_jacobian_ratio = std::min(q.min_jacobian_ratio, tet10_det(x, p[0], p[1], p[2]) / v_lin);
                    q.volume += tet10_volume(x);
                } else {
                    q.volume += v_lin / 6.0;
                }
                edges(x, tet_edges);
            }
            if (length < q.min_characteristic_length) {
                q.min_characteristic_length = length;
                q.shortest_block = b;
                q.shortest_element = e;
            }
            if (q.worst_block < 0 || sj < q.min_scaled_jacobian) {
                q.min_scaled_jacobian = std::min(q.min_scaled_jacobian, sj);
                q.worst_block = b;
                q.worst_element = e;
            }
        }
    }
    if (edge_count == 0) throw InputError("mesh_quality: the mesh has no solid elements (hex8, tet4, tet10)");
    q.mean_edge = edge_sum / edge_count;
    return q;
}

}  // namespace fem::finger
