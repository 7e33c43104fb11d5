#pragma once
// A linear FE model for implicit analysis (modal, static): which element blocks contribute, with which
// element routine, the supports and the couplings; assemble() gives the reduced sparse stiffness K and
// mass M of thesis Eq 2-36 after eliminating fixed and slave DOFs.
//
// Element families plug in through a kernel: a function from the element's node coordinates (and
// its index in the block) to its dense stiffness and mass, with `dofs_per_node` DOFs per node in the
// order ux, uy, uz[, rx, ry, rz] node after node, followed by the element's own internal DOFs if it
// has any (DOFs no other element shares and no support or coupling names, such as the bubble
// amplitudes of CalculiX's C3D8I: they enter K and M as equations after the nodal ones). Solids come
// ready-made (add_solid_part); a shell element is added with add_block(block, 6, kernel).
//
// Example: two parts joined by screws (coupled DOFs), clamped at the base, lowest ten modes:
//
//   fem::Model model(mesh);
//   model.add_solid_part("plate", steel);
//   model.add_solid_part("bracket", steel);
//   model.fix_node_set("base");                               // all DOFs of the set
//   model.couple_coincident(mesh.node_set("screw1_plate"), mesh.node_set("screw1_bracket"));
//   const fem::AssembledSystem sys = model.assemble();
//   const fem::modal::ModalResult modes = fem::modal::solve_modes(sys, {.modes = 10});
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "assembly/dof_map.hpp"
#include "core/types.hpp"
#include "element/solid_elements.hpp"
#include "material/elastic.hpp"
#include "mesh/mesh.hpp"

namespace fem {

struct ElementMatrices {
    Eigen::MatrixXd stiffness;  // (n * dofs_per_node) square
    Eigen::MatrixXd mass;       // same size
};

/// Element routine of one block: node coordinates and element index -> matrices.
using ElementKernel = std::function<ElementMatrices(std::span<const Vec3> x, int element)>;

struct SolidOptions {
    solid::MassKind mass = solid::MassKind::Consistent;
    bool incompatible_modes = true;  // hex8 only
    solid::Tet10MassRule tet10_mass_rule = solid::Tet10MassRule::Exact;
    solid::Tet4MassRule tet4_mass_rule = solid::Tet4MassRule::Exact;
    bool hex20_reduced = false;  // hex20: 2x2x2 Gauss for stiffness and mass (C3D20R), else 3x3x3 (C3D20)
};

/// The kernel of a linear solid block (hex8, hex20, tet4 or tet10) of material m; InputError for other shapes.
ElementKernel solid_kernel(ElementShape shape, const ElasticMaterial& m, const SolidOptions& options = {});

/// The kernel of a MITC4 shell block (quad4, 6 DOFs per node; element/shell_mitc4.hpp) of thickness
/// t and material m, with its consistent or lumped mass.
ElementKernel shell_kernel(double thickness, const ElasticMaterial& m, solid::MassKind mass = solid::MassKind::Consistent);

/// Reduced system: K and M hold the LOWER triangle only (use K.selfadjointView<Eigen::Lower>()),
/// both on the same sparsity pattern.
struct AssembledSystem {
    DofMap dofs;
    Constraints::Reduction reduction;
    int internal_dofs = 0;  // element-internal DOFs, numbered after the reduction.size nodal equations
    Eigen::SparseMatrix<double> stiffness, mass;

    int size() const { return reduction.size + internal_dofs; }
    /// Full nodal DOF vector (fixed DOFs zero, slaves equal to their master) from a reduced one
    /// (element-internal DOFs are not nodal: they are left out).
    Eigen::VectorXd expand(const Eigen::VectorXd& reduced) const;
    /// Nodal translations (ux, uy, uz per node, zero for nodes without DOFs) of a reduced vector:
    /// the point field for VTU output.
    std::vector<double> translations(const Eigen::VectorXd& reduced) const;
};

class Model {
public:
    /// The model keeps a reference to `mesh`, which must outlive it.
    explicit Model(const Mesh& mesh);

    /// Adds the elements of block `block` computed by `kernel` with `dofs_per_node` (3 or 6) and
    /// `internal_dofs` DOFs of each element's own (the kernel's matrices are then
    /// nodes x dofs_per_node + internal_dofs square, the internal DOFs last).
    void add_block(int block, int dofs_per_node, ElementKernel kernel, int internal_dofs = 0);
    /// Adds every block of part `part` as linear solids of material m.
    void add_solid_part(std::string_view part, const ElasticMaterial& m, const SolidOptions& options = {});
    /// Adds every block of part `part` as MITC4 shells (quad4 only) of thickness t.
    void add_shell_part(std::string_view part, double thickness, const ElasticMaterial& m,
                        solid::MassKind mass = solid::MassKind::Consistent);

    /// Supports: fixes the components (default all) of a node or of every node of a node set.
    void fix(int node, DofMask components = kAllDofs);
    void fix_node_set(std::string_view set, DofMask components = kAllDofs);
    void fix_nodes(const std::vector<int>& nodes, DofMask components = kAllDofs);

    /// Couples the components of all the given nodes (one ANSYS CP set per component).
    void couple(const std::vector<int>& nodes, DofMask components = kTranslations);
    /// Couples every node of `a` with the node of `b` at the same place (within `tolerance`, default
    /// 1e-9 of the model size): the screws of thesis Sec 2.4.2. Returns the number of pairs; throws
    /// InputError naming the first node of `a` without a partner.
    int couple_coincident(const std::vector<int>& a, const std::vector<int>& b, DofMask components = kTranslations,
                          double tolerance = -1.0);

    /// Assembles the reduced K and M. The sparsity pattern is built once from the connectivity and
    /// both matrices are scattered into it.
    AssembledSystem assemble() const;

    const Mesh& mesh() const { return mesh_; }
    /// The supports and couplings stated so far.
    const Constraints& constraints() const { return constraints_; }

private:
    struct Entry {
        int block;
        int dofs_per_node;
        ElementKernel kernel;
        int internal_dofs;
    };
    const Mesh& mesh_;
    std::vector<Entry> entries_;
    Constraints constraints_;
};

}  // namespace fem
