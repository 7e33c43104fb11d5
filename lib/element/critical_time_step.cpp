#include "element/critical_time_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/error.hpp"

namespace fem {

namespace cfl {
namespace {

double quad_area(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return 0.5 * (c - a).cross(d - b).norm();
}

// Volume of the trilinear hexahedron: det J is at most quadratic in each natural coordinate, so the
// 2x2x2 Gauss rule integrates it exactly.
double hexahedron_volume(const std::array<Vec3, 8>& x) {
    static constexpr double s[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                       {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    const double g = 1.0 / std::sqrt(3.0);
    double volume = 0.0;
    for (int q = 0; q < 8; ++q) {
        const double xi = s[q][0] * g, eta = s[q][1] * g, zeta = s[q][2] * g;
        Mat3 J = Mat3::Zero();  // columns: dx/dxi, dx/deta, dx/dzeta
        for (int a = 0; a < 8; ++a) {
            const double dxi = 0.125 * s[a][0] * (1 + s[a][1] * eta) * (1 + s[a][2] * zeta);
            const double deta = 0.125 * s[a][1] * (1 + s[a][0] * xi) * (1 + s[a][2] * zeta);
            const double dzeta = 0.125 * s[a][2] * (1 + s[a][0] * xi) * (1 + s[a][1] * eta);
            J.col(0) += dxi * x[a];
            J.col(1) += deta * x[a];
            J.col(2) += dzeta * x[a];
        }
        volume += J.determinant();  // Gauss weights are all 1
    }
    return volume;
}

template <std::size_t N>
std::array<Vec3, N> first_nodes(std::span<const Vec3> nodes) {
    std::array<Vec3, N> x;
    std::copy_n(nodes.begin(), N, x.begin());
    return x;
}

}  // namespace

double beam_length(const Vec3& a, const Vec3& b) { return (b - a).norm(); }

double triangle_shell_length(const std::array<Vec3, 3>& x) {
    const double area = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]).norm();
    const double longest = std::max({(x[1] - x[0]).norm(), (x[2] - x[1]).norm(), (x[0] - x[2]).norm()});
    return 2.0 * area / longest;
}

double quad_shell_length(const std::array<Vec3, 4>& x) {
    const double area = quad_area(x[0], x[1], x[2], x[3]);
    const double longest = std::max(
        {(x[1] - x[0]).norm(), (x[2] - x[1]).norm(), (x[3] - x[2]).norm(), (x[0] - x[3]).norm()});
    return area / longest;
}

double hexahedron_length(const std::array<Vec3, 8>& x) {
    static constexpr int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                        {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    double largest = 0.0;
    for (const auto& f : faces) largest = std::max(largest, quad_area(x[f[0]], x[f[1]], x[f[2]], x[f[3]]));
    return hexahedron_volume(x) / largest;
}

double tetrahedron_length(const std::array<Vec3, 4>& x) {
    const double volume = std::abs((x[1] - x[0]).dot((x[2] - x[0]).cross(x[3] - x[0]))) / 6.0;
    auto area = [&](int a, int b, int c) { return 0.5 * (x[b] - x[a]).cross(x[c] - x[a]).norm(); };
    const double largest = std::max({area(0, 1, 2), area(0, 1, 3), area(0, 2, 3), area(1, 2, 3)});
    return 3.0 * volume / largest;
}

double tet10_subtetrahedron_length(std::span<const Vec3> x) {
    if (x.size() < 10) throw InputError("tet10_subtetrahedron_length: a tet10 element needs 10 nodes, got " + std::to_string(x.size()));
    // Mid-edge node of the edge between corners i and j (Gmsh's tet10 order).
    auto mid = [&](int i, int j) -> const Vec3& {
        static const int edge[4][4] = {{-1, 4, 6, 7}, {4, -1, 5, 9}, {6, 5, -1, 8}, {7, 9, 8, -1}};
        return x[edge[i][j]];
    };
    auto altitude = [](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
        return tetrahedron_length({a, b, c, d});
    };
    double length = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 4; ++i) {  // corner tetrahedra: the corner and its three edges' mid-nodes
        int o[3], k = 0;
        for (int j = 0; j < 4; ++j)
            if (j != i) o[k++] = j;
        length = std::min(length, altitude(x[i], mid(i, o[0]), mid(i, o[1]), mid(i, o[2])));
    }
    // The inner octahedron: three pairs of opposite mid-nodes (01-23, 02-13, 03-12); split along the
    // shortest diagonal into four tetrahedra around it.
    const int pairs[3][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}};  // diagonal (i j)-(k l)
    int best = 0;
    for (int p = 1; p < 3; ++p)
        if ((mid(pairs[p][0], pairs[p][1]) - mid(pairs[p][2], pairs[p][3])).norm() <
            (mid(pairs[best][0], pairs[best][1]) - mid(pairs[best][2], pairs[best][3])).norm())
            best = p;
    const Vec3 &d0 = mid(pairs[best][0], pairs[best][1]), &d1 = mid(pairs[best][2], pairs[best][3]);
    // The four other mid-nodes form a ring around the diagonal: each shares a corner with its
    // neighbours in the ring (e.g. for the diagonal 01-23: 02, 03, 13, 12).
    const int a = pairs[best][0], b = pairs[best][1], c = pairs[best][2], d = pairs[best][3];
    const Vec3* ring[4] = {&mid(a, c), &mid(a, d), &mid(b, d), &mid(b, c)};
    for (int r = 0; r < 4; ++r) length = std::min(length, altitude(d0, d1, *ring[r], *ring[(r + 1) % 4]));
    return length;
}

double characteristic_length(ElementShape shape, std::span<const Vec3> nodes) {
    if (static_cast<int>(nodes.size()) < node_count(shape)) {
        std::ostringstream msg;
        msg << to_string(shape) << " element needs " << node_count(shape) << " nodes, got " << nodes.size();
        throw InputError(msg.str());
    }
    switch (shape) {
        case ElementShape::Point1: return std::numeric_limits<double>::infinity();
        case ElementShape::Beam2: return beam_length(nodes[0], nodes[1]);
        case ElementShape::Tri3: return triangle_shell_length(first_nodes<3>(nodes));
        case ElementShape::Quad4:
        case ElementShape::Quad8: return quad_shell_length(first_nodes<4>(nodes));
        case ElementShape::Tet4:
        case ElementShape::Tet10: return tetrahedron_length(first_nodes<4>(nodes));
        case ElementShape::Hex8:
        case ElementShape::Hex20: return hexahedron_length(first_nodes<8>(nodes));  // the corners
    }
    return 0.0;
}

double time_step(double length, double wave_speed) { return length / wave_speed; }

double solid_time_step(double length, double wave_speed, double volumetric_strain_rate,
                       const BulkViscosity& q) {
    const double Q = volumetric_strain_rate < 0.0
                         ? q.linear * wave_speed + q.quadratic * length * std::abs(volumetric_strain_rate)
                         : 0.0;
    return length / (Q + std::sqrt(Q * Q + wave_speed * wave_speed));
}

double flat_hexahedron_step_factor(double length_ratio, double linear) {
    const double xi = linear * std::max(1.0, 0.5 * length_ratio);
    return compression_step_factor(xi) / compression_step_factor(linear);
}

double compression_step_factor(double linear) { return std::sqrt(1.0 + linear * linear) - linear; }

double wave_speed(ElementShape shape, const ElasticMaterial& m) {
    switch (shape) {
        case ElementShape::Point1: return 0.0;
        case ElementShape::Beam2: return bar_wave_speed(m);
        case ElementShape::Tri3:
        case ElementShape::Quad4:
        case ElementShape::Quad8: return plate_wave_speed(m);
        case ElementShape::Tet4:
        case ElementShape::Tet10:
        case ElementShape::Hex8:
        case ElementShape::Hex20: return dilatational_wave_speed(m);
    }
    return 0.0;
}

double critical_time_step(ElementShape shape, std::span<const Vec3> nodes, const ElasticMaterial& m,
                          double volumetric_strain_rate, const BulkViscosity& q) {
    if (shape == ElementShape::Point1) return std::numeric_limits<double>::infinity();  // a point mass has no wave
    const double length = characteristic_length(shape, nodes);
    const double c = wave_speed(shape, m);
    switch (shape) {
        case ElementShape::Tet4:
        case ElementShape::Tet10:
        case ElementShape::Hex8:
        case ElementShape::Hex20: return solid_time_step(length, c, volumetric_strain_rate, q);
        default: return time_step(length, c);
    }
}

double density_scale_for_time_step(double dt_element, double dt_target) {
    if (!(dt_element > 0.0) || !(dt_target > 0.0))
        throw InputError("mass scaling needs positive time steps (element " + std::to_string(dt_element) +
                         " s, target " + std::to_string(dt_target) + " s)");
    const double r = dt_target / dt_element;
    return r > 1.0 ? r * r : 1.0;
}

}  // namespace cfl
}  // namespace fem
