#pragma once
// The finite element model of a design domain as the topology optimizer sees it (thesis Sec 2.6):
// elements with a reference stiffness matrix (at the solid Young's modulus E0), their DOF, volume
// and centroid, supports, several load cases, and passive regions (void or solid elements that the
// optimizer must not change). SIMP scales each element's matrix by its pseudo-density (Eq 2-48).
//
// Element matrices are stored once per distinct element geometry: on a regular grid every element
// shares one K_e, so building the model costs one element integration, not one per element.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "core/types.hpp"
#include "material/elastic.hpp"
#include "mesh/mesh.hpp"
#include "mesh/mesh_tools.hpp"  // nearest_node

namespace fem::topopt {

/// Role of an element in the optimization.
enum class Region : signed char {
    Design = 0,  // pseudo-density chosen by the optimizer
    Void = 1,    // held at the minimum density (a hole that must stay a hole)
    Solid = 2,   // held at density 1 (a bolt face, a bone: material that must stay)
};

/// A structured grid of quadrilaterals: the nodes form an (nx + 1) x (ny + 1) lattice (lattice point
/// (i, j) has index j (nx + 1) + i) and every element is one lattice cell. The multigrid solver
/// (topopt/multigrid.hpp) coarsens along it.
struct Grid {
    int nx = 0, ny = 0;
    std::vector<int> lattice_of_node;  // node -> lattice index
    std::vector<int> cell_of_element;  // element -> cell index j nx + i
};

/// The grid of a mesh whose Quad4 elements (all blocks, in block order) tile an axis-aligned lattice
/// in a plane z = const, one element per cell and one node per lattice point (rectangle_quads, a
/// transfinite Gmsh rectangle); nothing for any other mesh (cut, curved, Quad8, folded).
std::optional<Grid> structured_grid(const Mesh& mesh);

struct Model {
    int dofs_per_node = 2;
    int node_count = 0;
    int dofs_per_element = 0;
    std::vector<Eigen::MatrixXd> unique_stiffness;  // distinct element matrices at E0
    std::vector<int> stiffness_of;                  // element -> index into unique_stiffness
    std::vector<int> element_dofs;                  // dofs_per_element global DOF per element
    std::vector<double> volume;                     // element volumes (area x thickness) [m^3]
    std::vector<Vec3> centroid;                     // element centroids (for the filter) [m]
    std::vector<Region> region;                     // per element; all Design by default
    std::vector<char> fixed;                        // per DOF: 1 when supported (u = 0)
    std::vector<Eigen::VectorXd> loads;             // load cases, each a global force vector [N]
    std::optional<Grid> grid;                       // when the mesh is a structured grid (multigrid)

    int element_count() const { return static_cast<int>(stiffness_of.size()); }
    int dof_count() const { return node_count * dofs_per_node; }
    std::span<const int> dofs(int e) const {
        return {element_dofs.data() + static_cast<std::size_t>(e) * dofs_per_element,
                static_cast<std::size_t>(dofs_per_element)};
    }
    const Eigen::MatrixXd& stiffness(int e) const { return unique_stiffness[stiffness_of[e]]; }

    /// Supports component `component` (0 = x, 1 = y, ...) of node `node`. Throws InputError for a
    /// node or component out of range.
    void fix(int node, int component);
    /// Supports the listed components of every node of `nodes`; throws InputError when `nodes` is
    /// empty (`what` names the support in the message).
    void fix(std::span<const int> nodes, std::initializer_list<int> components, std::string_view what);
    /// Adds a point force to load case `load_case` (created when it does not exist yet); components
    /// beyond dofs_per_node must be zero (e.g. an out-of-plane force on a plane model): otherwise
    /// InputError.
    void add_force(int load_case, int node, const Vec3& force);
    /// Sets the region of every element whose centroid satisfies pred.
    template <class Pred>
    int mark(Region r, Pred pred) {
        int n = 0;
        for (int e = 0; e < element_count(); ++e)
            if (pred(centroid[e])) region[e] = r, ++n;
        return n;
    }
};

/// InputError naming E and the thickness when an element matrix is not finite (E = 1e308 Pa
/// overflows once multiplied by the strain-displacement products); callers add the element.
void require_finite_stiffness(const Eigen::MatrixXd& k, const ElasticMaterial& material, double thickness);

/// Plane-stress model (2 DOF per node) of every Quad4 or Quad8 element of `mesh` (all blocks, in
/// block order; one shape for the whole mesh), thickness `thickness`. Element matrices are
/// computed once per distinct geometry (translation-invariant comparison of the node coordinates).
/// Throws InputError for other shapes, mixed shapes, t <= 0 or an inverted element.
Model plane_stress_model(const Mesh& mesh, const ElasticMaterial& material, double thickness);

/// Flat-shell model (6 DOF per node: ux uy uz rx ry rz) of every Quad4 element of `mesh`, with the
/// MITC4 element of element/shell_mitc4.hpp, for folded plates loaded out of their plane (the
/// shackle body of thesis Sec 5.2.3). Element matrices are shared between elements of equal
/// geometry (translation-invariant comparison in 3D). Throws InputError for other shapes.
Model shell_model(const Mesh& mesh, const ElasticMaterial& material, double thickness);

// --- mesh helpers for design domains built from grids ----------------------------------------------

/// The mesh made of the elements of `mesh` whose centroid satisfies keep(centroid): unused nodes
/// are dropped and the remaining ones renumbered; node sets are mapped (members dropped with their
/// nodes). Used to cut non-rectangular design domains (a hole, an L, an ellipse) out of a grid.
template <class Keep>
Mesh crop(const Mesh& mesh, Keep keep);
Mesh crop_by_flags(const Mesh& mesh, const std::vector<char>& keep_element);

/// Nodes on the boundary of a mesh of quadrilaterals (on an edge used by one element only),
/// mid-side nodes of Quad8 included.
std::vector<int> boundary_nodes(const Mesh& mesh);


/// Element centroids of all blocks, in block order (average of the corner nodes).
std::vector<Vec3> element_centroids(const Mesh& mesh);

template <class Keep>
Mesh crop(const Mesh& mesh, Keep keep) {
    const auto c = element_centroids(mesh);
    std::vector<char> flags(c.size());
    for (std::size_t e = 0; e < c.size(); ++e) flags[e] = keep(c[e]) ? 1 : 0;
    return crop_by_flags(mesh, flags);
}

}  // namespace fem::topopt
