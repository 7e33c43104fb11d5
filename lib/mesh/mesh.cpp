#include "mesh/mesh.hpp"
#include "mesh/mesh_tools.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <sstream>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/memory.hpp"

namespace fem {

int Mesh::element_count() const {
    int n = 0;
    for (const auto& b : blocks) n += b.size();
    return n;
}

const std::vector<int>& Mesh::node_set(std::string_view name) const {
    auto it = node_sets.find(std::string(name));
    if (it != node_sets.end()) return it->second;
    std::ostringstream msg;
    msg << "node set '" << name << "' does not exist (known:";
    for (const auto& [n, ids] : node_sets) msg << ' ' << n;
    msg << ')';
    throw InputError(msg.str());
}

std::vector<int> Mesh::blocks_of_part(std::string_view part) const {
    std::vector<int> ids;
    for (int b = 0; b < static_cast<int>(blocks.size()); ++b)
        if (blocks[b].part == part) ids.push_back(b);
    if (ids.empty()) {
        std::ostringstream msg;
        msg << "part '" << part << "' has no elements (parts:";
        for (const auto& b : blocks) msg << ' ' << b.part;
        msg << ')';
        throw InputError(msg.str());
    }
    return ids;
}

std::vector<int> Mesh::nodes_of_part(std::string_view part) const {
    std::set<int> nodes;
    for (int b : blocks_of_part(part)) nodes.insert(blocks[b].connectivity.begin(), blocks[b].connectivity.end());
    return {nodes.begin(), nodes.end()};
}

std::vector<Vec3> Mesh::element_coordinates(int block, int e) const {
    std::vector<Vec3> x;
    for (int n : blocks[block].element(e)) x.push_back(nodes[n]);
    return x;
}

void Mesh::append(const Mesh& other) {
    const int offset = node_count();
    nodes.insert(nodes.end(), other.nodes.begin(), other.nodes.end());
    for (ElementBlock b : other.blocks) {
        for (int& n : b.connectivity) n += offset;
        blocks.push_back(std::move(b));
    }
    for (const auto& [name, ids] : other.node_sets) {
        auto& mine = node_sets[name];
        for (int n : ids) mine.push_back(n + offset);
    }
}

void Mesh::translate(const Vec3& offset) {
    for (auto& x : nodes) x += offset;
}

namespace {

// Nodes and elements are numbered with int: a generator asked for more is refused before it
// allocates anything (a 70000 x 70000 grid would overflow the node numbering).
void require_int_count(double nodes, double elements, const std::string& what) {
    constexpr double limit = std::numeric_limits<int>::max();
    if (nodes > limit || elements > limit)
        throw InputError(fmt::format("{} has {:.3g} nodes and {:.3g} elements; the library numbers both with 32-bit integers "
                                     "(at most {})", what, nodes, elements, std::numeric_limits<int>::max()));
    require_memory(nodes * sizeof(Vec3) + elements * 8 * sizeof(int), what);
}

}  // namespace

double centre_jacobian(ElementShape shape, const std::vector<Vec3>& x) {
    switch (shape) {
        case ElementShape::Tet4:
        case ElementShape::Tet10: return (x[1] - x[0]).dot((x[2] - x[0]).cross(x[3] - x[0]));
        case ElementShape::Hex8:
        case ElementShape::Hex20: {  // the corners
            const Vec3 a = (x[1] + x[2] + x[5] + x[6]) - (x[0] + x[3] + x[4] + x[7]);
            const Vec3 b = (x[2] + x[3] + x[6] + x[7]) - (x[0] + x[1] + x[4] + x[5]);
            const Vec3 c = (x[4] + x[5] + x[6] + x[7]) - (x[0] + x[1] + x[2] + x[3]);
            return a.dot(b.cross(c));
        }
        default: return 1.0;
    }
}

void validate(const Mesh& mesh) {
    for (int i = 0; i < mesh.node_count(); ++i)
        if (!mesh.nodes[i].allFinite()) throw InputError("node " + std::to_string(i) + " has a non-finite coordinate");
    for (int b = 0; b < static_cast<int>(mesh.blocks.size()); ++b) {
        const auto& block = mesh.blocks[b];
        if (block.connectivity.size() % block.nodes_per_element() != 0)
            throw InputError("block " + std::to_string(b) + " (part '" + block.part + "'): connectivity length is not a multiple of " +
                             std::to_string(block.nodes_per_element()));
        if (!block.ids.empty() && static_cast<int>(block.ids.size()) != block.size())
            throw InputError("block " + std::to_string(b) + " (part '" + block.part + "'): " + std::to_string(block.ids.size()) +
                             " element numbers for " + std::to_string(block.size()) + " elements");
        for (int e = 0; e < block.size(); ++e) {
            auto conn = block.element(e);
            for (std::size_t k = 0; k < conn.size(); ++k) {
                if (conn[k] < 0 || conn[k] >= mesh.node_count())
                    throw InputError("part '" + block.part + "' element " + std::to_string(block.id(e)) + " refers to node " +
                                     std::to_string(conn[k]) + ", which does not exist");
                for (std::size_t j = 0; j < k; ++j)
                    if (conn[j] == conn[k])
                        throw InputError("part '" + block.part + "' element " + std::to_string(block.id(e)) + " repeats node " +
                                         std::to_string(conn[k]));
            }
            if (dimension(block.shape) == 3 && centre_jacobian(block.shape, mesh.element_coordinates(b, e)) <= 0.0)
                throw InputError("part '" + block.part + "' " + std::string(to_string(block.shape)) + " element " +
                                 std::to_string(block.id(e)) + " is inverted (non-positive Jacobian at its centre)");
        }
    }
    for (const auto& [name, ids] : mesh.node_sets)
        for (int n : ids)
            if (n < 0 || n >= mesh.node_count())
                throw InputError("node set '" + name + "' refers to node " + std::to_string(n) + ", which does not exist");
}

Mesh box_hex8(double lx, double ly, double lz, int nx, int ny, int nz, std::string part) {
    if (nx < 1 || ny < 1 || nz < 1) throw InputError("box_hex8 needs at least one element per direction");
    require_int_count((nx + 1.0) * (ny + 1.0) * (nz + 1.0), 1.0 * nx * ny * nz, fmt::format("a {} x {} x {} hex8 box", nx, ny, nz));
    Mesh m;
    auto id = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) m.add_node(Vec3(lx * i / nx, ly * j / ny, lz * k / nz));
    ElementBlock b{std::move(part), ElementShape::Hex8, {}};
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const int e[8] = {id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
                                  id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
                b.add(e);
            }
    m.blocks.push_back(std::move(b));
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) {
                const int n = id(i, j, k);
                if (i == 0) m.node_sets["x0"].push_back(n);
                if (i == nx) m.node_sets["x1"].push_back(n);
                if (j == 0) m.node_sets["y0"].push_back(n);
                if (j == ny) m.node_sets["y1"].push_back(n);
                if (k == 0) m.node_sets["z0"].push_back(n);
                if (k == nz) m.node_sets["z1"].push_back(n);
            }
    return m;
}

Mesh box_hex20(double lx, double ly, double lz, int nx, int ny, int nz, std::string part) {
    const Mesh hex = box_hex8(lx, ly, lz, nx, ny, nz, part);
    Mesh m;
    m.nodes = hex.nodes;
    m.node_sets = hex.node_sets;
    std::map<std::pair<int, int>, int> mid;  // edge (sorted corner pair) -> mid-edge node
    static constexpr int kEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                          {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    ElementBlock b{std::move(part), ElementShape::Hex20, {}};
    for (int e = 0; e < hex.blocks[0].size(); ++e) {
        const auto c = hex.blocks[0].element(e);
        int nodes[20];
        for (int k = 0; k < 8; ++k) nodes[k] = c[k];
        for (int k = 0; k < 12; ++k) {
            const int a = c[kEdges[k][0]], z = c[kEdges[k][1]];
            const auto key = std::minmax(a, z);
            auto it = mid.find(key);
            if (it == mid.end()) it = mid.emplace(key, m.add_node(0.5 * (hex.nodes[a] + hex.nodes[z]))).first;
            nodes[8 + k] = it->second;
        }
        b.add(nodes);
    }
    m.blocks.push_back(std::move(b));
    // A mid-edge node lies on a face when both ends of its edge do.
    for (auto& [name, ids] : m.node_sets) {
        const std::set<int> on(ids.begin(), ids.end());
        for (const auto& [edge, node] : mid)
            if (on.count(edge.first) && on.count(edge.second)) ids.push_back(node);
        std::sort(ids.begin(), ids.end());
    }
    return m;
}

Mesh box_tets(double lx, double ly, double lz, int nx, int ny, int nz, ElementShape shape, std::string part) {
    if (shape != ElementShape::Tet4 && shape != ElementShape::Tet10)
        throw InputError("box_tets makes tet4 or tet10 elements, not " + std::string(to_string(shape)));
    const Mesh hex = box_hex8(lx, ly, lz, nx, ny, nz, part);
    Mesh m;
    m.nodes = hex.nodes;
    ElementBlock b{std::move(part), shape, {}};
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int c) {
        const auto key = std::minmax(a, c);
        auto it = mid.find(key);
        if (it != mid.end()) return it->second;
        const int id = m.add_node(0.5 * (m.nodes[a] + m.nodes[c]));
        mid.emplace(key, id);
        return id;
    };
    // Hex corner of the lattice offset (i, j, k) in box_hex8's node order; the six tetrahedra walk
    // from corner (0,0,0) to (1,1,1) one axis at a time, in every order of the axes.
    const int corner[2][2][2] = {{{0, 4}, {3, 7}}, {{1, 5}, {2, 6}}};  // [i][j][k]
    const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int e = 0; e < hex.blocks[0].size(); ++e) {
        const auto h = hex.blocks[0].element(e);
        for (const auto& p : perms) {
            int step[3] = {0, 0, 0};
            int v[4];
            v[0] = h[corner[0][0][0]];
            for (int s = 0; s < 3; ++s) {
                step[p[s]] = 1;
                v[s + 1] = h[corner[step[0]][step[1]][step[2]]];
            }
            const Vec3 &x0 = m.nodes[v[0]], &x1 = m.nodes[v[1]], &x2 = m.nodes[v[2]], &x3 = m.nodes[v[3]];
            if ((x1 - x0).dot((x2 - x0).cross(x3 - x0)) < 0) std::swap(v[1], v[2]);
            if (shape == ElementShape::Tet4) {
                b.add(v);
            } else {
                const int t[10] = {v[0], v[1], v[2], v[3], midpoint(v[0], v[1]), midpoint(v[1], v[2]),
                                   midpoint(v[0], v[2]), midpoint(v[0], v[3]), midpoint(v[2], v[3]), midpoint(v[1], v[3])};
                b.add(t);
            }
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

Mesh rectangle_quads(double lx, double ly, int nx, int ny, ElementShape shape, std::string part) {
    if (nx < 1 || ny < 1) throw InputError("rectangle_quads needs at least one element per direction");
    if (shape != ElementShape::Quad4 && shape != ElementShape::Quad8)
        throw InputError("rectangle_quads makes quad4 or quad8 elements, not " + std::string(to_string(shape)));
    {
        const double s = shape == ElementShape::Quad8 ? 2 : 1;  // grid points per element edge
        require_int_count((s * nx + 1) * (s * ny + 1), 1.0 * nx * ny,
                          fmt::format("a {} x {} {} grid", nx, ny, to_string(shape)));
    }
    Mesh m;
    const bool serendipity = shape == ElementShape::Quad8;
    // Quad8 uses a grid of half-spacing with the element-centre points left out.
    const int sx = serendipity ? 2 : 1;
    const int gx = sx * nx, gy = sx * ny;
    std::vector<int> id((gx + 1) * (gy + 1), -1);
    for (int j = 0; j <= gy; ++j)
        for (int i = 0; i <= gx; ++i) {
            if (serendipity && i % 2 == 1 && j % 2 == 1) continue;
            const int n = m.add_node(Vec3(lx * i / gx, ly * j / gy, 0.0));
            id[j * (gx + 1) + i] = n;
            if (i == 0) m.node_sets["x0"].push_back(n);
            if (i == gx) m.node_sets["x1"].push_back(n);
            if (j == 0) m.node_sets["y0"].push_back(n);
            if (j == gy) m.node_sets["y1"].push_back(n);
        }
    auto at = [&](int i, int j) { return id[j * (gx + 1) + i]; };
    ElementBlock b{std::move(part), shape, {}};
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const int i0 = sx * i, j0 = sx * j;
            if (!serendipity) {
                const int e[4] = {at(i0, j0), at(i0 + 1, j0), at(i0 + 1, j0 + 1), at(i0, j0 + 1)};
                b.add(e);
            } else {
                const int e[8] = {at(i0, j0),     at(i0 + 2, j0),     at(i0 + 2, j0 + 2), at(i0, j0 + 2),
                                  at(i0 + 1, j0), at(i0 + 2, j0 + 1), at(i0 + 1, j0 + 2), at(i0, j0 + 1)};
                b.add(e);
            }
        }
    m.blocks.push_back(std::move(b));
    return m;
}

Mesh parallelogram_quad4(const Vec3& centre, const Vec3& u, const Vec3& v, int nu, int nv, std::string part) {
    if (nu < 1 || nv < 1 || !(u.cross(v).norm() > 0.0))
        throw InputError("parallelogram_quad4 '" + part + "': needs nu, nv >= 1 and non-parallel u, v");
    std::vector<double> a(nu + 1), b(nv + 1);
    for (int i = 0; i <= nu; ++i) a[i] = static_cast<double>(i) / nu - 0.5;
    for (int j = 0; j <= nv; ++j) b[j] = static_cast<double>(j) / nv - 0.5;
    return graded_parallelogram_quad4(centre, u, v, a, b, std::move(part));
}

Mesh line_beam2(const Vec3& a, const Vec3& b, int n, std::string part) {
    if (n < 1) throw InputError("line_beam2 needs at least one element");
    require_int_count(n + 1.0, n, fmt::format("a line of {} beam elements", n));
    Mesh m;
    for (int i = 0; i <= n; ++i) m.add_node(a + (b - a) * (static_cast<double>(i) / n));
    ElementBlock blk{std::move(part), ElementShape::Beam2, {}};
    for (int i = 0; i < n; ++i) {
        const int e[2] = {i, i + 1};
        blk.add(e);
    }
    m.blocks.push_back(std::move(blk));
    m.node_sets["start"] = {0};
    m.node_sets["end"] = {n};
    return m;
}

}  // namespace fem
