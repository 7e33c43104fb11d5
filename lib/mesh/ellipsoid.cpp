#include "mesh/ellipsoid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fem {

namespace {

// The signed volume of a hexahedron at its centre (Jacobian determinant x 8), for orientation.
double centre_jacobian(const std::array<Vec3, 8>& p) {
    const Vec3 dx = 0.25 * ((p[1] - p[0]) + (p[2] - p[3]) + (p[5] - p[4]) + (p[6] - p[7]));
    const Vec3 dy = 0.25 * ((p[3] - p[0]) + (p[2] - p[1]) + (p[7] - p[4]) + (p[6] - p[5]));
    const Vec3 dz = 0.25 * ((p[4] - p[0]) + (p[5] - p[1]) + (p[6] - p[2]) + (p[7] - p[3]));
    return dx.dot(dy.cross(dz));
}

}  // namespace

Mesh hex_ellipsoid(const Vec3& axes, const EllipsoidGrid& g, bool half, std::string part) {
    if (!(axes.minCoeff() > 0.0))
        throw InputError(fmt::format("hex_ellipsoid '{}': semi-axes ({}, {}, {}) must be > 0", part, axes.x(), axes.y(), axes.z()));
    if (g.nx < 1 || g.ny < 1 || g.nz < 1 || g.layers < 1 || !(g.inner_scale > 0.0 && g.inner_scale * std::sqrt(3.0) < 1.0))
        throw InputError(fmt::format("hex_ellipsoid '{}': needs nx, ny, nz, layers >= 1 and 0 < inner_scale < 1 / sqrt(3) "
                                     "(got {}, {}, {}, {}, {})", part, g.nx, g.ny, g.nz, g.layers, g.inner_scale));
    if (half && g.nz % 2 != 0)
        throw InputError(fmt::format("hex_ellipsoid '{}': a half model needs an even nz (got {})", part, g.nz));
    const std::array<int, 3> n{g.nx, g.ny, g.nz};
    const double s = g.inner_scale;
    Mesh m;
    // Nodes are keyed by their logical position: inner-block lattice index (i, j, k) for layer 0
    // (the inner block and its surface), and (face-independent) lattice index + layer for the ring
    // layers, so that nodes shared by neighbouring faces are created once.
    std::map<std::tuple<int, int, int, int>, int> ids;
    auto logical = [&](int i, int j, int k) {
        return Vec3(-1.0 + 2.0 * i / n[0], -1.0 + 2.0 * j / n[1], -1.0 + 2.0 * k / n[2]);
    };
    auto node = [&](int i, int j, int k, int layer) {
        const auto key = std::make_tuple(i, j, k, layer);
        if (auto it = ids.find(key); it != ids.end()) return it->second;
        const Vec3 q = logical(i, j, k);
        const double t = static_cast<double>(layer) / g.layers;
        Vec3 p = (1.0 - t) * s * q + (layer > 0 ? Vec3(t * q / q.norm()) : Vec3::Zero());
        p = p.cwiseProduct(axes);
        if (std::abs(q.z()) < 1e-14) p.z() = 0.0;  // exactly on the cut plane
        const int id = m.add_node(p);
        ids.emplace(key, id);
        return id;
    };
    ElementBlock block{part, ElementShape::Hex8, {}};
    auto add = [&](std::array<int, 8> e, double zc) {
        if (half && zc > 0.0) return;
        std::array<Vec3, 8> p;
        for (int a = 0; a < 8; ++a) p[a] = m.nodes[e[a]];
        if (centre_jacobian(p) < 0.0) std::swap_ranges(e.begin(), e.begin() + 4, e.begin() + 4);
        block.add(e);
    };
    // Inner block.
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i)
                add({node(i, j, k, 0), node(i + 1, j, k, 0), node(i + 1, j + 1, k, 0), node(i, j + 1, k, 0),
                     node(i, j, k + 1, 0), node(i + 1, j, k + 1, 0), node(i + 1, j + 1, k + 1, 0), node(i, j + 1, k + 1, 0)},
                    logical(i, j, k).z() + 1.0 / n[2]);
    // Ring layers on the six faces: face (axis d, side), its lattice over the other two axes.
    for (int d = 0; d < 3; ++d)
        for (int side = 0; side < 2; ++side) {
            const int u = (d + 1) % 3, v = (d + 2) % 3;
            for (int b = 0; b < n[v]; ++b)
                for (int a = 0; a < n[u]; ++a)
                    for (int l = 0; l < g.layers; ++l) {
                        auto at = [&](int da, int db, int dl) {
                            std::array<int, 3> idx{};
                            idx[d] = side * n[d], idx[u] = a + da, idx[v] = b + db;
                            return node(idx[0], idx[1], idx[2], l + dl);
                        };
                        std::array<int, 3> c{};
                        c[d] = side * n[d], c[u] = a, c[v] = b;
                        double zc = logical(c[0], c[1], c[2]).z();
                        if (d != 2) zc += 1.0 / n[2];  // centre of the face cell in z
                        add({at(0, 0, 0), at(1, 0, 0), at(1, 1, 0), at(0, 1, 0), at(0, 0, 1), at(1, 0, 1), at(1, 1, 1), at(0, 1, 1)},
                            zc);
                    }
        }
    m.blocks.push_back(std::move(block));
    // Drop nodes that no kept element uses (the discarded half), renumbering.
    std::vector<int> used(m.node_count(), -1);
    for (int c : m.blocks[0].connectivity) used[c] = 0;
    std::vector<Vec3> kept;
    for (int i = 0; i < m.node_count(); ++i)
        if (used[i] == 0) used[i] = static_cast<int>(kept.size()), kept.push_back(m.nodes[i]);
    for (int& c : m.blocks[0].connectivity) c = used[c];
    m.nodes = std::move(kept);
    for (const auto& [key, id] : ids) {
        if (used[id] < 0) continue;
        const auto [i, j, k, layer] = key;
        const int nid = used[id];
        if (half && std::abs(m.nodes[nid].z()) == 0.0) m.node_sets["symmetry"].push_back(nid);
        if (layer == g.layers) m.node_sets["surface"].push_back(nid);
        if (layer == 0 && 2 * i == n[0] && 2 * j == n[1] && 2 * k == n[2]) m.node_sets["centre"] = {nid};
    }
    for (auto& [name, set] : m.node_sets) std::sort(set.begin(), set.end());
    validate(m);
    return m;
}

}  // namespace fem
