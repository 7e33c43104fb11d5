#include "mesh/mesh_tools.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

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

namespace {
// The node graph of the mesh in compressed rows: the neighbours of node i are adj[start[i] ..
// start[i + 1]), increasing (two nodes are neighbours when an element holds both).
struct NodeGraph {
    std::vector<int> start, adj;
    int degree(int i) const { return start[i + 1] - start[i]; }
};

NodeGraph node_graph(const Mesh& mesh) {
    const int n = mesh.node_count();
    // Elements of each node (compressed rows), then each node's neighbours through them.
    std::vector<int> count(n + 1, 0);
    for (const ElementBlock& b : mesh.blocks)
        for (int a : b.connectivity) ++count[a + 1];
    std::partial_sum(count.begin(), count.end(), count.begin());
    struct Incidence { int block, element; };
    std::vector<Incidence> of(count[n]);
    std::vector<int> fill(count.begin(), count.end() - 1);
    for (int bi = 0; bi < static_cast<int>(mesh.blocks.size()); ++bi) {
        const ElementBlock& b = mesh.blocks[bi];
        for (int e = 0; e < b.size(); ++e)
            for (int a : b.element(e)) of[fill[a]++] = {bi, e};
    }
    NodeGraph g;
    g.start.assign(n + 1, 0);
    std::vector<int> row;
    for (int i = 0; i < n; ++i) {
        row.clear();
        for (int k = count[i]; k < count[i + 1]; ++k)
            for (int a : mesh.blocks[of[k].block].element(of[k].element))
                if (a != i) row.push_back(a);
        std::sort(row.begin(), row.end());
        row.erase(std::unique(row.begin(), row.end()), row.end());
        g.adj.insert(g.adj.end(), row.begin(), row.end());
        g.start[i + 1] = static_cast<int>(g.adj.size());
    }
    return g;
}

// Breadth-first level structure rooted at `root` within its connected part: the nodes level by
// level into `levels` (cleared first), the start of each level into `level_start`. `seen` marks
// visited nodes with `stamp` (a new stamp per search: no clearing).
void level_structure(const NodeGraph& g, int root, std::vector<int>& seen, int stamp, std::vector<int>& levels,
                     std::vector<int>& level_start) {
    levels.assign(1, root);
    level_start.assign(1, 0);
    seen[root] = stamp;
    for (std::size_t begin = 0; begin < levels.size();) {
        const std::size_t end = levels.size();
        for (std::size_t k = begin; k < end; ++k)
            for (int j = g.start[levels[k]]; j < g.start[levels[k] + 1]; ++j)
                if (seen[g.adj[j]] != stamp) {
                    seen[g.adj[j]] = stamp;
                    levels.push_back(g.adj[j]);
                }
        level_start.push_back(static_cast<int>(end));
        begin = end;
    }
    // level_start holds the start of every level and, last, the total count.
}
}  // namespace

std::vector<int> reverse_cuthill_mckee(const Mesh& mesh) {
    const int n = mesh.node_count();
    const NodeGraph g = node_graph(mesh);
    std::vector<int> order, seen(n, -1), levels, level_start, queue, next;
    order.reserve(n);
    std::vector<char> numbered(n, 0);
    int stamp = 0;
    auto by_degree = [&](int a, int b) { return g.degree(a) != g.degree(b) ? g.degree(a) < g.degree(b) : a < b; };
    for (int first = 0; first < n; ++first) {
        if (numbered[first]) continue;
        // The connected part of `first`; its node of least degree starts the search for a
        // pseudo-peripheral node (George and Liu's algorithm): from the last level, the node of least
        // degree, as long as the depth of the level structure grows.
        level_structure(g, first, seen, stamp++, levels, level_start);
        int root = *std::min_element(levels.begin(), levels.end(), by_degree);
        level_structure(g, root, seen, stamp++, levels, level_start);
        for (;;) {
            const int depth = static_cast<int>(level_start.size());
            const int candidate = *std::min_element(levels.begin() + level_start[depth - 2], levels.end(), by_degree);
            std::vector<int> candidate_levels, candidate_start;
            level_structure(g, candidate, seen, stamp++, candidate_levels, candidate_start);
            if (static_cast<int>(candidate_start.size()) <= depth) break;
            root = candidate;
            levels = std::move(candidate_levels);
            level_start = std::move(candidate_start);
        }
        // Cuthill-McKee from the root: each node's unnumbered neighbours in increasing degree.
        const std::size_t part_begin = order.size();
        order.push_back(root);
        numbered[root] = 1;
        for (std::size_t k = part_begin; k < order.size(); ++k) {
            next.clear();
            for (int j = g.start[order[k]]; j < g.start[order[k] + 1]; ++j)
                if (!numbered[g.adj[j]]) {
                    numbered[g.adj[j]] = 1;
                    next.push_back(g.adj[j]);
                }
            std::sort(next.begin(), next.end(), by_degree);
            order.insert(order.end(), next.begin(), next.end());
        }
        std::reverse(order.begin() + static_cast<std::ptrdiff_t>(part_begin), order.end());
    }
    return order;
}

int node_bandwidth(const Mesh& mesh) {
    int width = 0;
    for (const ElementBlock& b : mesh.blocks)
        for (int e = 0; e < b.size(); ++e) {
            const auto nodes = b.element(e);
            const auto [lo, hi] = std::minmax_element(nodes.begin(), nodes.end());
            width = std::max(width, *hi - *lo);
        }
    return width;
}

void renumber_nodes(Mesh& mesh, std::span<const int> order) {
    const int n = mesh.node_count();
    if (static_cast<int>(order.size()) != n)
        throw InputError(fmt::format("renumber_nodes: the order lists {} nodes, the mesh has {}", order.size(), n));
    std::vector<int> to(n, -1);  // old -> new
    for (int k = 0; k < n; ++k) {
        const int old = order[k];
        if (old < 0 || old >= n || to[old] >= 0)
            throw InputError(fmt::format("renumber_nodes: entry {} of the order ({}) is not a node or repeats one", k, old));
        to[old] = k;
    }
    std::vector<Vec3> nodes(n);
    for (int k = 0; k < n; ++k) nodes[k] = mesh.nodes[order[k]];
    mesh.nodes = std::move(nodes);
    for (auto& b : mesh.blocks)
        for (int& a : b.connectivity) a = to[a];
    for (auto& [name, ids] : mesh.node_sets)
        for (int& a : ids) a = to[a];
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
