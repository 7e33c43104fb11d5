#include "mesh/mesh_tools.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fem {

Mesh graded_parallelogram_quad4(const Vec3& origin, const Vec3& u, const Vec3& v, std::span<const double> a,
                                std::span<const double> b, std::string part) {
    auto increasing = [](std::span<const double> x) {
        if (x.size() < 2) return false;
        for (std::size_t i = 1; i < x.size(); ++i)
            if (!(x[i] > x[i - 1])) return false;
        return true;
    };
    if (!increasing(a) || !increasing(b) || !(u.cross(v).norm() > 0.0))
        throw InputError(fmt::format("quad4 grid '{}': needs at least two strictly increasing row and column coordinates "
                                     "and non-parallel u, v",
                                     part));
    const int na = static_cast<int>(a.size()), nb = static_cast<int>(b.size());
    Mesh m;
    for (int j = 0; j < nb; ++j)
        for (int i = 0; i < na; ++i) m.add_node(origin + a[i] * u + b[j] * v);
    ElementBlock blk{std::move(part), ElementShape::Quad4, {}};
    for (int j = 0; j + 1 < nb; ++j)
        for (int i = 0; i + 1 < na; ++i) {
            const int n = j * na + i;
            const int e[4] = {n, n + 1, n + na + 1, n + na};
            blk.add(e);
        }
    m.blocks.push_back(std::move(blk));
    return m;
}

int weld_coincident_nodes(Mesh& mesh, double tol) {
    if (!(tol > 0.0)) throw InputError(fmt::format("weld_coincident_nodes: tolerance {} must be positive", tol));
    std::map<std::array<long long, 3>, int> at;  // rounded coordinates -> new node number
    std::vector<int> to(mesh.node_count());
    std::vector<Vec3> kept;
    for (int i = 0; i < mesh.node_count(); ++i) {
        const Vec3& x = mesh.nodes[i];
        const std::array<long long, 3> key = {std::llround(x.x() / tol), std::llround(x.y() / tol), std::llround(x.z() / tol)};
        const auto [it, inserted] = at.try_emplace(key, static_cast<int>(kept.size()));
        if (inserted) kept.push_back(x);
        to[i] = it->second;
    }
    const int removed = mesh.node_count() - static_cast<int>(kept.size());
    mesh.nodes = std::move(kept);
    for (auto& b : mesh.blocks)
        for (int& n : b.connectivity) n = to[n];
    for (auto& [name, ids] : mesh.node_sets) {
        std::vector<int> out;
        for (int n : ids)
            if (std::find(out.begin(), out.end(), to[n]) == out.end()) out.push_back(to[n]);
        ids = std::move(out);
    }
    return removed;
}

namespace {
// The candidate at position k is node_at(k); one loop for the candidate list and for the whole mesh
// (not std::views::iota: clang 14, which builds `make fuzz`, rejects libstdc++ 12's iota_view).
template <class NodeAt>
int nearest_of(const Mesh& mesh, const Vec3& p, std::size_t count, NodeAt node_at) {
    int best = -1;
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < count; ++k) {
        const int i = node_at(k);
        if (const double di = (mesh.nodes.at(i) - p).squaredNorm(); di < d) d = di, best = i;
    }
    if (best < 0) throw InputError("nearest_node: no node to choose from");
    return best;
}
}  // namespace

int nearest_node(const Mesh& mesh, const Vec3& p, std::span<const int> candidates) {
    return nearest_of(mesh, p, candidates.size(), [&](std::size_t k) { return candidates[k]; });
}

int nearest_node(const Mesh& mesh, const Vec3& p) {
    return nearest_of(mesh, p, static_cast<std::size_t>(mesh.node_count()),
                      [](std::size_t k) { return static_cast<int>(k); });
}

void reflect(Mesh& mesh, const Vec3& point, const Vec3& normal) {
    if (!(normal.norm() > 0.0) || !normal.allFinite() || !point.allFinite())
        throw InputError("reflect: the mirror plane's normal has zero length or is not finite");
    const Vec3 n = normal.normalized();
    for (Vec3& x : mesh.nodes) x -= 2.0 * (x - point).dot(n) * n;
    // The new order of each element's nodes (new[i] = old[perm[i]]).
    auto permutation = [](const ElementBlock& b) -> std::vector<int> {
        switch (b.shape) {
            case ElementShape::Point1: return {0};
            case ElementShape::Beam2: return {0, 1};
            case ElementShape::Tri3: return {0, 2, 1};
            case ElementShape::Quad4: return {0, 3, 2, 1};
            case ElementShape::Tet4: return {0, 2, 1, 3};
            // Gmsh order: corners, edges 01, 12, 02, 03, 23, 13; corners 1 <-> 2 swaps 01 <-> 02, 23 <-> 13.
            case ElementShape::Tet10: return {0, 2, 1, 3, 6, 5, 4, 7, 9, 8};
            case ElementShape::Hex8: return {4, 5, 6, 7, 0, 1, 2, 3};
            default:
                throw InputError(fmt::format("reflect: block '{}' has {} elements, which reflect cannot renumber", b.part,
                                             to_string(b.shape)));
        }
    };
    for (auto& b : mesh.blocks) {
        const std::vector<int> perm = permutation(b);
        const int k = b.nodes_per_element();
        std::vector<int> old(k);
        for (int e = 0; e < b.size(); ++e) {
            int* c = b.connectivity.data() + static_cast<std::size_t>(e) * k;
            std::copy(c, c + k, old.begin());
            for (int i = 0; i < k; ++i) c[i] = old[perm[i]];
        }
    }
}

}  // namespace fem
