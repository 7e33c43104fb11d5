#include "assembly/model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include "core/error.hpp"
#include "element/shell_mitc4.hpp"

namespace fem {

ElementKernel solid_kernel(ElementShape shape, const ElasticMaterial& m, const SolidOptions& o) {
    switch (shape) {
        case ElementShape::Hex8:
            return [m, o](std::span<const Vec3> x, int) {
                return ElementMatrices{solid::hex8_stiffness(x, m, o.incompatible_modes), solid::hex8_mass(x, m.density, o.mass)};
            };
        case ElementShape::Tet10:
            return [m, o](std::span<const Vec3> x, int) {
                return ElementMatrices{solid::tet10_stiffness(x, m), solid::tet10_mass(x, m.density, o.mass, o.tet10_mass_rule)};
            };
        case ElementShape::Hex20:
            return [m, o](std::span<const Vec3> x, int) {
                return ElementMatrices{solid::hex20_stiffness(x, m, o.hex20_reduced),
                                       solid::hex20_mass(x, m.density, o.mass, o.hex20_reduced)};
            };
        case ElementShape::Tet4:
            return [m, o](std::span<const Vec3> x, int) {
                return ElementMatrices{solid::tet4_stiffness(x, m), solid::tet4_mass(x, m.density, o.mass, o.tet4_mass_rule)};
            };
        default:
            throw InputError("no linear solid element for shape " + std::string(to_string(shape)) +
                             " (the modal solver has hex8, hex20, tet4 and tet10)");
    }
}

ElementKernel shell_kernel(double thickness, const ElasticMaterial& m, solid::MassKind mass) {
    return [thickness, m, mass](std::span<const Vec3> x, int) {
        const std::array<Vec3, 4> xs = {x[0], x[1], x[2], x[3]};
        const shell::ShellMatrices s = shell::mitc4_matrices(xs, thickness, m);
        return ElementMatrices{s.stiffness, mass == solid::MassKind::Lumped ? s.lumped_mass : s.consistent_mass};
    };
}

Eigen::VectorXd AssembledSystem::expand(const Eigen::VectorXd& reduced) const {
    Eigen::VectorXd full = Eigen::VectorXd::Zero(dofs.size());
    for (int i = 0; i < dofs.size(); ++i)
        if (const int r = reduction.reduced_of_full[i]; r >= 0) full(i) = reduced(r);
    return full;
}

std::vector<double> AssembledSystem::translations(const Eigen::VectorXd& reduced) const {
    std::vector<double> u(3 * static_cast<std::size_t>(dofs.node_count()), 0.0);
    for (int n = 0; n < dofs.node_count(); ++n)
        for (int c = 0; c < 3; ++c)
            if (const int d = dofs.dof(n, c); d >= 0)
                if (const int r = reduction.reduced_of_full[d]; r >= 0) u[3 * n + c] = reduced(r);
    return u;
}

Model::Model(const Mesh& mesh) : mesh_(mesh) {}

void Model::add_block(int block, int dofs_per_node, ElementKernel kernel, int internal_dofs) {
    if (block < 0 || block >= static_cast<int>(mesh_.blocks.size()))
        throw InputError("model: block " + std::to_string(block) + " does not exist");
    if (dofs_per_node != 3 && dofs_per_node != 6)
        throw InputError("model: block " + std::to_string(block) + " asks for " + std::to_string(dofs_per_node) +
                         " DOFs per node (3 or 6)");
    if (internal_dofs < 0)
        throw InputError("model: block " + std::to_string(block) + " asks for " + std::to_string(internal_dofs) + " internal DOFs");
    entries_.push_back({block, dofs_per_node, std::move(kernel), internal_dofs});
}

void Model::add_solid_part(std::string_view part, const ElasticMaterial& m, const SolidOptions& options) {
    for (int b : mesh_.blocks_of_part(part)) add_block(b, 3, solid_kernel(mesh_.blocks[b].shape, m, options));
}

void Model::add_shell_part(std::string_view part, double thickness, const ElasticMaterial& m, solid::MassKind mass) {
    for (int b : mesh_.blocks_of_part(part)) {
        if (mesh_.blocks[b].shape != ElementShape::Quad4)
            throw InputError("part '" + std::string(part) + "': shells are quad4 (MITC4), not " +
                             std::string(to_string(mesh_.blocks[b].shape)));
        add_block(b, 6, shell_kernel(thickness, m, mass));
    }
}

void Model::fix(int node, DofMask components) { constraints_.fix(node, components); }
void Model::fix_nodes(const std::vector<int>& nodes, DofMask components) {
    for (int n : nodes) constraints_.fix(n, components);
}
void Model::fix_node_set(std::string_view set, DofMask components) { fix_nodes(mesh_.node_set(set), components); }
void Model::couple(const std::vector<int>& nodes, DofMask components) { constraints_.couple(nodes, components); }

int Model::couple_coincident(const std::vector<int>& a, const std::vector<int>& b, DofMask components, double tolerance) {
    if (tolerance < 0) {
        Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
        for (const Vec3& x : mesh_.nodes) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
        tolerance = 1e-9 * std::max((hi - lo).norm(), 1e-300);
    }
    // Bucket b's nodes on a grid of cell `tolerance`; a partner lies in the 27 cells around.
    auto cell = [&](const Vec3& x) {
        return std::tuple<long long, long long, long long>(std::llround(x.x() / tolerance), std::llround(x.y() / tolerance),
                                                           std::llround(x.z() / tolerance));
    };
    std::multimap<std::tuple<long long, long long, long long>, int> grid;
    for (int n : b) grid.emplace(cell(mesh_.nodes.at(n)), n);
    int pairs = 0;
    for (int n : a) {
        const Vec3& x = mesh_.nodes.at(n);
        const auto [i, j, k] = cell(x);
        int partner = -1;
        for (long long di = -1; di <= 1 && partner < 0; ++di)
            for (long long dj = -1; dj <= 1 && partner < 0; ++dj)
                for (long long dk = -1; dk <= 1 && partner < 0; ++dk) {
                    auto [lo, hi] = grid.equal_range({i + di, j + dj, k + dk});
                    for (auto it = lo; it != hi; ++it)
                        if (it->second != n && (mesh_.nodes[it->second] - x).norm() <= tolerance) {
                            partner = it->second;
                            break;
                        }
                }
        if (partner < 0)
            throw InputError("coupling: node " + std::to_string(n) + " at (" + std::to_string(x.x()) + ", " +
                             std::to_string(x.y()) + ", " + std::to_string(x.z()) + ") has no coincident partner");
        constraints_.couple({n, partner}, components);
        ++pairs;
    }
    return pairs;
}

AssembledSystem Model::assemble() const {
    if (entries_.empty()) throw InputError("model: no element block was added");
    AssembledSystem sys;
    sys.dofs = DofMap(mesh_.node_count());
    for (const Entry& e : entries_)
        for (int n : mesh_.blocks[e.block].connectivity) sys.dofs.require(n, e.dofs_per_node);
    sys.dofs.finalize();
    sys.reduction = constraints_.reduce(sys.dofs);
    const auto& red = sys.reduction.reduced_of_full;
    if (sys.reduction.size == 0) throw InputError("model: every DOF is fixed; nothing to solve");
    // Element-internal DOFs follow the nodal equations, block entry after block entry.
    std::vector<int> first_internal;
    for (const Entry& en : entries_) {
        first_internal.push_back(sys.reduction.size + sys.internal_dofs);
        sys.internal_dofs += mesh_.blocks[en.block].size() * en.internal_dofs;
    }
    const int n = sys.size();

    // Reduced DOF of local DOF k of element e (block entry k_entry), -1 when eliminated.
    auto element_dofs = [&](std::size_t k_entry, int e, std::vector<int>& out) {
        const Entry& en = entries_[k_entry];
        out.clear();
        for (int node : mesh_.blocks[en.block].element(e))
            for (int c = 0; c < en.dofs_per_node; ++c) out.push_back(red[sys.dofs.dof(node, c)]);
        for (int k = 0; k < en.internal_dofs; ++k) out.push_back(first_internal[k_entry] + e * en.internal_dofs + k);
    };

    // 1. Pattern (lower triangle, column-wise), built once from the connectivity.
    std::vector<std::vector<int>> rows_of(n);
    std::vector<int> ed;
    for (std::size_t k = 0; k < entries_.size(); ++k)
        for (int e = 0; e < mesh_.blocks[entries_[k].block].size(); ++e) {
            element_dofs(k, e, ed);
            for (int j : ed)
                if (j >= 0)
                    for (int i : ed)
                        if (i >= j) rows_of[j].push_back(i);
        }
    std::vector<int> outer(n + 1, 0), inner;
    for (int j = 0; j < n; ++j) {
        auto& r = rows_of[j];
        std::sort(r.begin(), r.end());
        r.erase(std::unique(r.begin(), r.end()), r.end());
        outer[j + 1] = outer[j] + static_cast<int>(r.size());
    }
    inner.reserve(outer[n]);
    for (auto& r : rows_of) {
        inner.insert(inner.end(), r.begin(), r.end());
        std::vector<int>().swap(r);
    }
    std::vector<double> kval(inner.size(), 0.0), mval(inner.size(), 0.0);

    // 2. Scatter every element into the pattern.
    for (std::size_t k = 0; k < entries_.size(); ++k) {
        const Entry& en = entries_[k];
        const ElementBlock& block = mesh_.blocks[en.block];
        const int ndof = block.nodes_per_element() * en.dofs_per_node + en.internal_dofs;
        std::vector<Vec3> x;
        for (int e = 0; e < block.size(); ++e) {
            x.clear();
            for (int node : block.element(e)) x.push_back(mesh_.nodes[node]);
            ElementMatrices m;
            try {
                m = en.kernel(x, e);
            } catch (const InputError& err) {
                throw InputError("part '" + block.part + "' " + std::string(to_string(block.shape)) + " element " +
                                 std::to_string(e) + ": " + err.what());
            }
            if (m.stiffness.rows() != ndof || m.stiffness.cols() != ndof || m.mass.rows() != ndof || m.mass.cols() != ndof)
                throw std::logic_error("element kernel of part '" + block.part + "' returned matrices of the wrong size");
            element_dofs(k, e, ed);
            for (int b = 0; b < ndof; ++b) {
                const int j = ed[b];
                if (j < 0) continue;
                const int* col_begin = inner.data() + outer[j];
                const int* col_end = inner.data() + outer[j + 1];
                for (int a = 0; a < ndof; ++a) {
                    const int i = ed[a];
                    if (i < j) continue;  // also skips eliminated (-1)
                    const auto pos = std::lower_bound(col_begin, col_end, i) - inner.data();
                    kval[pos] += m.stiffness(a, b);
                    mval[pos] += m.mass(a, b);
                }
            }
        }
    }
    const auto nnz = static_cast<Eigen::Index>(inner.size());
    sys.stiffness = Eigen::Map<const Eigen::SparseMatrix<double>>(n, n, nnz, outer.data(), inner.data(), kval.data());
    sys.mass = Eigen::Map<const Eigen::SparseMatrix<double>>(n, n, nnz, outer.data(), inner.data(), mval.data());
    return sys;
}

}  // namespace fem
