#pragma once
// Test meshes: a box of tet10 elements made by splitting each hexahedron of box_hex8 into six
// tetrahedra around its main diagonal (a conforming split on a structured grid), with mid-edge
// nodes shared between neighbours. Node sets of box_hex8 ("x0", "x1", ...) are extended to the
// mid-edge nodes on those faces.
#include <array>
#include <map>
#include <string>
#include <utility>

#include "mesh/mesh.hpp"

namespace fem::test {

inline Mesh box_tet10(double lx, double ly, double lz, int nx, int ny, int nz, std::string part = "box") {
    const Mesh hex = box_hex8(lx, ly, lz, nx, ny, nz, part);
    Mesh m;
    m.nodes = hex.nodes;
    ElementBlock b{part, ElementShape::Tet10, {}};
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int c) {
        const auto key = std::minmax(a, c);
        auto it = mid.find(key);
        if (it != mid.end()) return it->second;
        const int id = m.add_node(0.5 * (m.nodes[a] + m.nodes[c]));
        mid.emplace(key, id);
        return id;
    };
    // Hex corner index of the lattice offset (i, j, k) in box_hex8's order.
    const int corner[2][2][2] = {{{0, 4}, {3, 7}}, {{1, 5}, {2, 6}}};  // [i][j][k]
    const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int e = 0; e < hex.blocks[0].size(); ++e) {
        const auto h = hex.blocks[0].element(e);
        for (const auto& p : perms) {
            int step[3] = {0, 0, 0};
            std::array<int, 4> v;
            v[0] = h[corner[0][0][0]];
            for (int s = 0; s < 3; ++s) {
                step[p[s]] = 1;
                v[s + 1] = h[corner[step[0]][step[1]][step[2]]];
            }
            const Vec3 &x0 = m.nodes[v[0]], &x1 = m.nodes[v[1]], &x2 = m.nodes[v[2]], &x3 = m.nodes[v[3]];
            if ((x1 - x0).dot((x2 - x0).cross(x3 - x0)) < 0) std::swap(v[1], v[2]);
            // Gmsh order: corners, then edges 01, 12, 02, 03, 23, 13.
            const int t[10] = {v[0], v[1], v[2], v[3], midpoint(v[0], v[1]), midpoint(v[1], v[2]),
                               midpoint(v[0], v[2]), midpoint(v[0], v[3]), midpoint(v[2], v[3]), midpoint(v[1], v[3])};
            b.add(t);
        }
    }
    m.blocks.push_back(std::move(b));
    const double eps = 1e-9 * (lx + ly + lz);
    m.node_sets["x0"] = m.select_nodes([&](const Vec3& x) { return x.x() < eps; });
    m.node_sets["x1"] = m.select_nodes([&](const Vec3& x) { return x.x() > lx - eps; });
    m.node_sets["y0"] = m.select_nodes([&](const Vec3& x) { return x.y() < eps; });
    m.node_sets["y1"] = m.select_nodes([&](const Vec3& x) { return x.y() > ly - eps; });
    m.node_sets["z0"] = m.select_nodes([&](const Vec3& x) { return x.z() < eps; });
    m.node_sets["z1"] = m.select_nodes([&](const Vec3& x) { return x.z() > lz - eps; });
    return m;
}

}  // namespace fem::test
