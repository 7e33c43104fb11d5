#include "topopt/model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include <fmt/format.h>

#include "core/error.hpp"
#include "element/plane_stress.hpp"

namespace fem::topopt {

void Model::fix(int node, int component) {
    if (node < 0 || node >= node_count)
        throw InputError(fmt::format("support on node {}: the model has nodes 0..{}", node, node_count - 1));
    if (component < 0 || component >= dofs_per_node)
        throw InputError(fmt::format("support on node {}: component {} does not exist ({} DOF per node)", node,
                                     component, dofs_per_node));
    fixed[static_cast<std::size_t>(node) * dofs_per_node + component] = 1;
}

void Model::fix(std::span<const int> nodes, std::initializer_list<int> components, std::string_view what) {
    if (nodes.empty()) throw InputError(fmt::format("support '{}' selects no node", what));
    for (int n : nodes)
        for (int c : components) fix(n, c);
}

void Model::add_force(int load_case, int node, const Vec3& force) {
    if (load_case < 0) throw InputError(fmt::format("load case {} is negative", load_case));
    if (node < 0 || node >= node_count)
        throw InputError(fmt::format("load on node {}: the model has nodes 0..{}", node, node_count - 1));
    for (int c = dofs_per_node; c < 3; ++c)
        if (force(c) != 0.0)
            throw InputError(fmt::format("load on node {}: component {} = {} N acts out of the model's plane "
                                         "({} DOF per node)", node, c, force(c), dofs_per_node));
    while (static_cast<int>(loads.size()) <= load_case) loads.push_back(Eigen::VectorXd::Zero(dof_count()));
    for (int c = 0; c < std::min(dofs_per_node, 3); ++c)
        loads[load_case](static_cast<Eigen::Index>(node) * dofs_per_node + c) += force(c);
}

std::vector<Vec3> element_centroids(const Mesh& mesh) {
    std::vector<Vec3> c;
    c.reserve(mesh.element_count());
    for (const auto& b : mesh.blocks) {
        // Average of the corners (the first 4 nodes of a Quad8): the centre of a straight-sided quad.
        const int corners = (b.shape == ElementShape::Quad8) ? 4 : b.nodes_per_element();
        for (int e = 0; e < b.size(); ++e) {
            Vec3 s = Vec3::Zero();
            auto nodes = b.element(e);
            for (int k = 0; k < corners; ++k) s += mesh.nodes[nodes[k]];
            c.push_back(s / corners);
        }
    }
    return c;
}

void require_finite_stiffness(const Eigen::MatrixXd& k, const ElasticMaterial& material, double thickness) {
    if (k.allFinite()) return;
    throw InputError(fmt::format("the element stiffness overflows double precision with E = {:g} Pa and thickness {:g} m "
                                 "(check the units: SI, Pa and m)", material.youngs_modulus, thickness));
}

std::optional<Grid> structured_grid(const Mesh& mesh) {
    if (mesh.blocks.empty() || mesh.node_count() == 0) return std::nullopt;
    for (const auto& b : mesh.blocks)
        if (b.shape != ElementShape::Quad4) return std::nullopt;
    Vec3 lo = mesh.nodes.front(), hi = lo;
    for (const auto& p : mesh.nodes) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const double tol = 1e-9 * (hi - lo).norm();
    if (hi.z() - lo.z() > tol) return std::nullopt;
    // The distinct x and y coordinates (merged within tol) are the lattice lines.
    auto lines = [&](int axis) {
        std::vector<double> v;
        for (const auto& p : mesh.nodes) v.push_back(p(axis));
        std::sort(v.begin(), v.end());
        std::vector<double> out{v.front()};
        for (double t : v)
            if (t - out.back() > tol) out.push_back(t);
        return out;
    };
    const auto xs = lines(0), ys = lines(1);
    Grid g;
    g.nx = static_cast<int>(xs.size()) - 1;
    g.ny = static_cast<int>(ys.size()) - 1;
    if (g.nx < 1 || g.ny < 1 || static_cast<long long>(g.nx + 1) * (g.ny + 1) != mesh.node_count() ||
        static_cast<long long>(g.nx) * g.ny != mesh.element_count())
        return std::nullopt;
    auto index = [&](const std::vector<double>& v, double t) {
        return static_cast<int>(std::lower_bound(v.begin(), v.end(), t - tol) - v.begin());
    };
    std::vector<char> taken((g.nx + 1) * (g.ny + 1), 0);
    g.lattice_of_node.resize(mesh.node_count());
    for (int n = 0; n < mesh.node_count(); ++n) {
        const int k = index(ys, mesh.nodes[n].y()) * (g.nx + 1) + index(xs, mesh.nodes[n].x());
        if (taken[k]) return std::nullopt;
        taken[k] = 1;
        g.lattice_of_node[n] = k;
    }
    std::vector<char> used(static_cast<std::size_t>(g.nx) * g.ny, 0);
    for (const auto& b : mesh.blocks)
        for (int e = 0; e < b.size(); ++e) {
            int imin = g.nx, jmin = g.ny, imax = -1, jmax = -1;
            for (int n : b.element(e)) {
                const int k = g.lattice_of_node[n], i = k % (g.nx + 1), j = k / (g.nx + 1);
                imin = std::min(imin, i), imax = std::max(imax, i), jmin = std::min(jmin, j), jmax = std::max(jmax, j);
            }
            if (imax != imin + 1 || jmax != jmin + 1) return std::nullopt;  // not one lattice cell
            const int cell = jmin * g.nx + imin;
            if (used[cell]) return std::nullopt;
            used[cell] = 1;
            g.cell_of_element.push_back(cell);
        }
    return g;
}

Model plane_stress_model(const Mesh& mesh, const ElasticMaterial& material, double thickness) {
    if (mesh.blocks.empty() || mesh.element_count() == 0) throw InputError("topology model: the mesh has no elements");
    const ElementShape shape = mesh.blocks.front().shape;
    for (const auto& b : mesh.blocks)
        if (b.shape != shape)
            throw InputError(fmt::format("topology model: block '{}' is {}, but the mesh starts with {} "
                                         "(one element shape per model)", b.part, to_string(b.shape), to_string(shape)));
    if (shape != ElementShape::Quad4 && shape != ElementShape::Quad8)
        throw InputError(fmt::format("topology model: plane-stress elements are quad4 or quad8, not {}", to_string(shape)));
    if (!(thickness > 0)) throw InputError(fmt::format("topology model: thickness must be > 0, got {}", thickness));

    Model m;
    m.dofs_per_node = 2;
    m.node_count = mesh.node_count();
    const int n = node_count(shape);
    m.dofs_per_element = 2 * n;
    m.fixed.assign(m.dof_count(), 0);
    m.centroid = element_centroids(mesh);
    m.region.assign(m.centroid.size(), Region::Design);

    // Distinct geometries: node coordinates relative to the first node, rounded to 1e-9 of the
    // element's size (a translated copy of an element has the same stiffness matrix).
    std::map<std::vector<long long>, int> known;
    std::vector<Vec3> x(n);
    std::vector<long long> key(2 * n);
    for (std::size_t bi = 0; bi < mesh.blocks.size(); ++bi) {
        const auto& b = mesh.blocks[bi];
        for (int e = 0; e < b.size(); ++e) {
            auto nodes = b.element(e);
            for (int k = 0; k < n; ++k) {
                if (nodes[k] < 0 || nodes[k] >= m.node_count)
                    throw InputError(fmt::format("topology model: block '{}' element {} uses node {} (mesh has {})",
                                                 b.part, e, nodes[k], m.node_count));
                x[k] = mesh.nodes[nodes[k]];
                m.element_dofs.push_back(2 * nodes[k]);
                m.element_dofs.push_back(2 * nodes[k] + 1);
            }
            double size = 0;
            for (int k = 1; k < n; ++k) size = std::max(size, (x[k] - x[0]).head<2>().norm());
            const double q = size * 1e-9;
            for (int k = 0; k < n; ++k) {
                key[2 * k] = std::llround((x[k].x() - x[0].x()) / q);
                key[2 * k + 1] = std::llround((x[k].y() - x[0].y()) / q);
            }
            auto [it, inserted] = known.try_emplace(key, static_cast<int>(m.unique_stiffness.size()));
            if (inserted) {
                try {
                    m.unique_stiffness.push_back(
                        plane::stiffness(shape, x, material.youngs_modulus, material.poissons_ratio, thickness));
                    require_finite_stiffness(m.unique_stiffness.back(), material, thickness);
                } catch (const InputError& err) {
                    throw InputError(fmt::format("block '{}' element {}: {}", b.part, e, err.what()));
                }
            }
            m.stiffness_of.push_back(it->second);
            m.volume.push_back(plane::area(shape, x) * thickness);
        }
    }
    m.grid = structured_grid(mesh);
    return m;
}

Mesh crop_by_flags(const Mesh& mesh, const std::vector<char>& keep) {
    if (static_cast<int>(keep.size()) != mesh.element_count())
        throw InputError("crop: one flag per element expected");
    std::vector<int> new_id(mesh.node_count(), -1);
    Mesh out;
    std::size_t e_global = 0;
    for (const auto& b : mesh.blocks) {
        ElementBlock nb{b.part, b.shape, {}, {}};
        for (int e = 0; e < b.size(); ++e, ++e_global) {
            if (!keep[e_global]) continue;
            nb.ids.push_back(b.id(e));  // the kept elements keep their numbers
            for (int node : b.element(e)) {
                if (new_id[node] < 0) new_id[node] = -2;  // mark used; numbered below in old order
                nb.connectivity.push_back(node);
            }
        }
        out.blocks.push_back(std::move(nb));
    }
    // Number the kept nodes in their original order (keeps the grid's bandwidth).
    for (int i = 0; i < mesh.node_count(); ++i)
        if (new_id[i] == -2) new_id[i] = out.add_node(mesh.nodes[i]);
    for (auto& b : out.blocks)
        for (int& node : b.connectivity) node = new_id[node];
    std::erase_if(out.blocks, [](const ElementBlock& b) { return b.connectivity.empty(); });
    for (const auto& [name, nodes] : mesh.node_sets) {
        std::vector<int> kept;
        for (int node : nodes)
            if (new_id[node] >= 0) kept.push_back(new_id[node]);
        out.node_sets[name] = std::move(kept);
    }
    return out;
}

std::vector<int> boundary_nodes(const Mesh& mesh) {
    // An edge is identified by its two corner nodes; boundary edges belong to one element only.
    std::map<std::pair<int, int>, std::pair<int, std::vector<int>>> edges;
    for (const auto& b : mesh.blocks) {
        if (b.shape != ElementShape::Quad4 && b.shape != ElementShape::Quad8)
            throw InputError("boundary_nodes: quadrilateral meshes only");
        for (int e = 0; e < b.size(); ++e) {
            auto nd = b.element(e);
            for (int k = 0; k < 4; ++k) {
                const int a = nd[k], c = nd[(k + 1) % 4];
                auto& entry = edges[{std::min(a, c), std::max(a, c)}];
                ++entry.first;
                entry.second = {a, c};
                if (b.shape == ElementShape::Quad8) entry.second.push_back(nd[4 + k]);
            }
        }
    }
    std::vector<char> on(mesh.node_count(), 0);
    for (const auto& [key, entry] : edges)
        if (entry.first == 1)
            for (int node : entry.second) on[node] = 1;
    std::vector<int> ids;
    for (int i = 0; i < mesh.node_count(); ++i)
        if (on[i]) ids.push_back(i);
    return ids;
}

}  // namespace fem::topopt
