// The flat-shell design model (MITC4) of the topology optimizer, for folded plates.
#include <array>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "core/error.hpp"
#include "element/shell_mitc4.hpp"
#include "topopt/model.hpp"

namespace fem::topopt {

Model shell_model(const Mesh& mesh, const ElasticMaterial& material, double thickness) {
    if (mesh.blocks.empty() || mesh.element_count() == 0) throw InputError("shell topology model: the mesh has no elements");
    for (const auto& b : mesh.blocks)
        if (b.shape != ElementShape::Quad4)
            throw InputError(fmt::format("shell topology model: block '{}' is {}; the MITC4 shell needs quad4",
                                         b.part, to_string(b.shape)));
    if (!(thickness > 0)) throw InputError(fmt::format("shell topology model: thickness must be > 0, got {}", thickness));
    Model m;
    m.dofs_per_node = 6;
    m.node_count = mesh.node_count();
    m.dofs_per_element = 24;
    m.fixed.assign(m.dof_count(), 0);
    m.centroid = element_centroids(mesh);
    m.region.assign(m.centroid.size(), Region::Design);
    std::map<std::vector<long long>, int> known;
    std::array<Vec3, 4> x;
    std::vector<long long> key(12);
    for (const auto& b : mesh.blocks)
        for (int e = 0; e < b.size(); ++e) {
            auto nodes = b.element(e);
            for (int k = 0; k < 4; ++k) {
                x[k] = mesh.nodes[nodes[k]];
                for (int c = 0; c < 6; ++c) m.element_dofs.push_back(6 * nodes[k] + c);
            }
            double size = 0;
            for (int k = 1; k < 4; ++k) size = std::max(size, (x[k] - x[0]).norm());
            for (int k = 0; k < 4; ++k)
                for (int c = 0; c < 3; ++c) key[3 * k + c] = std::llround((x[k](c) - x[0](c)) / (size * 1e-9));
            auto [it, inserted] = known.try_emplace(key, static_cast<int>(m.unique_stiffness.size()));
            double area = 0;
            if (inserted) {
                try {
                    const auto mats = shell::mitc4_matrices(x, thickness, material);
                    m.unique_stiffness.emplace_back(mats.stiffness);
                    require_finite_stiffness(m.unique_stiffness.back(), material, thickness);
                } catch (const InputError& err) {
                    throw InputError(fmt::format("block '{}' element {}: {}", b.part, e, err.what()));
                }
            }
            // Area of a (possibly warped) quadrilateral: half the cross product of the diagonals.
            area = 0.5 * (x[2] - x[0]).cross(x[3] - x[1]).norm();
            m.stiffness_of.push_back(it->second);
            m.volume.push_back(area * thickness);
        }
    m.grid = structured_grid(mesh);
    return m;
}

}  // namespace fem::topopt
