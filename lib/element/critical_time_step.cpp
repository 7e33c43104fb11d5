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
        case ElementShape::Hex8: return hexahedron_length(first_nodes<8>(nodes));
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

double wave_speed(ElementShape shape, const ElasticMaterial& m) {
    switch (shape) {
        case ElementShape::Point1: return 0.0;
        case ElementShape::Beam2: return bar_wave_speed(m);
        case ElementShape::Tri3:
        case ElementShape::Quad4:
        case ElementShape::Quad8: return plate_wave_speed(m);
        case ElementShape::Tet4:
        case ElementShape::Tet10:
        case ElementShape::Hex8: return dilatational_wave_speed(m);
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
        case ElementShape::Hex8: return solid_time_step(length, c, volumetric_strain_rate, q);
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
