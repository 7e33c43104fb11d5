#pragma once
// Tetrahedral element groups of the explicit solver (4-node constant strain and 10-node quadratic
// tetrahedra, element/tet_explicit.hpp), for the Gmsh finger meshes of thesis Cases C and D.
//
// Time step. Table 2-1 gives the tetrahedron the minimum altitude over the dilatational wave
// speed: the tet4's rule, not a bound for the tet10, whose highest mode lives on the node spacing
// (half an edge). Each element alone (its 30 x 30 linear stiffness against its HRZ masses, dense
// eigen-solve) has 2 / omega_e = 0.26..0.34 x its Table 2-1 step on every shape tried, regular to
// sliver and needle, nu 0.3..0.49 (tests/explicit/test_tet_explicit.cpp); other lumpings do not help
// (corner masses 1/32, 1/24, 1/20, 1/10 of the element move it by -18..+6 %): the lumping is not
// the cause. So the group's reference step for each element is its own limit 2 / omega_e (the
// element bound: omega_max of the assembled lumped-mass system <= max_e omega_e, Irons; Hughes Sec
// 9.1.5), and selective mass scaling, which lifts every element whose reference step is below its
// target, lifts exactly the elements that set the limit: a mass_scaling_dt of a tet10 model is a
// guaranteed step (keyed on Table 2-1 steps it gave about 0.37 x the target). Every cycle the
// element's step follows its deformation as its Table 2-1 step does (altitudes shrink in
// compression, the bulk-viscosity Q term): r x (2 / omega_e) x T_e(current) / T_e(reference), the
// tet10's current length taken at its 4 integration points (tet::critical_time_step_tet10: its
// corners alone can flatten while it is barely strained, which cut the grasp model's step 40 %). The
// solver measures omega_max of all its solid groups together once at the start (Lanczos,
// ExplicitSolver) and hands each group the factor r = (2 / omega_max) / (smallest reference step);
// r >= 1 when tetrahedra control (the assembled limit exceeds the element bound: 1.6 on the Table 5-3
// bird, 2.1 on a Gmsh finger), so the step at rest is exactly 2 / omega_max (before the 0.9 of Eq
// 2-27). Stiffness damping beta lowers it as for the hexahedron: dt <= (2 / omega)(sqrt(1 + xi^2) -
// xi), xi = beta omega / 2, applied after r. The element bound alone is the fallback when the
// Lanczos measurement does not converge (element_omega_bound).
//
// Usage (a finger meshed with Gmsh in tet10, part "finger"):
//   ExplicitModel model(mesh);
//   add_tets(model, "finger", rubber, {.rayleigh_beta = 0.0});
#include <array>
#include <string_view>
#include <vector>

#include "element/critical_time_step.hpp"
#include "element/tet_explicit.hpp"
#include "explicit/element_group.hpp"
#include "explicit/parallel.hpp"
#include "material/elastic.hpp"

namespace fem {

class ExplicitModel;

/// Options of a tetrahedral part (LS-DYNA *SECTION_SOLID ELFORM 10/16 + *CONTROL_BULK_VISCOSITY).
struct TetGroupOptions {
    bool bulk_viscosity = true;   // Table 2-1 Q terms
    BulkViscosity bulk{};         // C0 = 1.5, C1 = 0.06
    double rayleigh_beta = 0.0;   // stiffness-proportional damping beta of Eq 2-39 [s]
};

/// A block of tet4 (N = 4, one point) or tet10 (N = 10, four points) elements, one material.
template <int N, int Q>
class TetGroup final : public ElementGroup {
public:
    TetGroup(const Mesh& mesh, int block, const ElasticMaterial& material, const TetGroupOptions& options = {});
    std::string kind() const override { return N == 4 ? "tet4" : "tet10"; }
    int size() const override { return static_cast<int>(refs_.size()); }
    std::vector<int> nodes() const override { return nodes_; }
    double add_lumped_mass(NodalState& s) const override;
    double mass() const override;
    std::vector<double> reference_time_steps() const override;
    void set_mass_scaling(std::vector<double> factor) override;
    GroupForceResult internal_forces(NodalState& s, bool compute_dt) override;
    std::vector<double> element_stress() const override;
    bool adds_viscous_forces() const override { return kmat_.bulk_viscosity || beta_ > 0.0; }
    double bulk_viscosity_linear() const override { return kmat_.bulk_viscosity ? kmat_.bulk.linear : 0.0; }
    bool set_stability_factor(double r) override;
    double element_omega_bound() const override;

    const ElasticMaterial& material() const { return material_; }
    const hex8::Hex8Material& kernel_material() const { return kmat_; }
    const tet::Reference<N, Q>& reference(int e) const { return refs_[e]; }
    /// Blocks of kLanes straight-sided tet10s packed with one Jacobian each (tet::pack_straight).
    int straight_blocks() const { return static_cast<int>(straight_.size()); }
    const std::array<int, N>& connectivity(int e) const { return conn_[e]; }
    /// Element e's lumped nodal masses (unscaled).
    const std::array<double, N>& lumped_mass(int e) const { return mass_[e]; }
    /// The factor on the Table 2-1 steps in use (set by the solver's measurement; 1 before).
    double stability_factor() const { return factor_; }
    std::string time_step_rule(int e) const override;
    /// r_e = (2 / omega_e) / Table 2-1 step of the reference element (the element bound).
    double element_stability_ratio(int e) const { return element_ratio_[e]; }
    /// Number of colours of the element chunks (barriers per force evaluation on several threads).
    int colour_count() const { return static_cast<int>(colouring_.colours.size()); }

    /// Elements per chunk: the unit of the deterministic partition (energy partial sums, colouring).
    /// Smaller than the hexahedron's (each element is 2-4 x the work; the finger meshes have
    /// 5,000-20,000 elements, and each colour needs enough chunks to keep two threads busy).
    static constexpr int kChunk = 256;

private:
    // As Hex8Group (groups.hpp): everything public is in the block's element order; each cycle
    // works in the kernel order (elements sorted by their smallest node, par::node_order), in
    // blocks of hex8::kLanes elements (one per lane of the kernel), chunks of kChunk elements
    // coloured so that chunks of one colour share no node, each element adding its forces straight
    // into the nodal forces (par::ChunkColouring): the same bits on any number of threads.
    ElasticMaterial material_;
    hex8::Hex8Material kmat_;
    double beta_ = 0.0;
    std::vector<std::array<int, N>> conn_;     // block order
    std::vector<tet::Reference<N, Q>> refs_;   // block order
    std::vector<std::array<double, N>> mass_;  // block order
    std::vector<double> element_ratio_, element_omega_, table_dt_, mass_scale_;  // block order
    double factor_ = 1.0;
    std::vector<int> nodes_;                   // the group's nodes, increasing
    std::vector<int> order_;                   // kernel position k -> element (block order)
    std::vector<std::array<int, N>> kconn_;    // connectivity in kernel order
    // The kernel's reference data in kernel order, blocks of kLanes elements; the lanes of the last
    // block past the end repeat the last element.
    // A tet10 block whose kLanes elements are all straight-sided (tet::pack_straight) is kept in
    // straight_ instead (11 instead of 41 doubles per element): slot_[block] >= 0 indexes packed_,
    // < 0 straight_ at -1 - slot_. Tet4: every block in packed_.
    std::vector<tet::TetPackedBlock<Q>> packed_;
    std::vector<tet::TetPackedBlock<1>> straight_;
    std::vector<int> slot_;
    std::vector<double> step_scale_;           // kernel order: element_ratio_ x sqrt(mass_scale_)
    std::vector<double> von_mises_sq_;         // kernel order (sqrt on output)
    double dt_wave_speed_ = 0.0;               // Table 2-1 dilatational wave speed
    par::ChunkColouring colouring_;
    std::vector<ChunkSums> partial_;  // one per chunk
};

using Tet4Group = TetGroup<4, 1>;
using Tet10Group = TetGroup<10, 4>;

/// Adds a Tet4Group or Tet10Group for every block of `part`; InputError when the part has a block
/// of another shape (hexahedra: ExplicitModel::add_hex8) or no block.
void add_tets(ExplicitModel& model, std::string_view part, const ElasticMaterial& material,
              const TetGroupOptions& options = {});

}  // namespace fem
