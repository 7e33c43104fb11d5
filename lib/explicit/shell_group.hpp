#pragma once
// Shell element group of the explicit solver: 4-node Belytschko-Tsay shells (LS-DYNA formulation
// 2, the thesis's Shell 163) and 3-node triangles as degenerate quadrilaterals, one material and
// one thickness per part. The formulation is in ../element/shell_bt_explicit.hpp.
//
// Nodes of a shell part carry rotations (NodalState::rotation, omega, moment, inertia).
//  * Mass: lumped, rho t A / 4 per node (triangles rho t A / 3); isotropic rotational inertia
//    scaled so that the rotations never control the step (shellbt::rotational_inertia: about
//    m A / 8 for a thin square element at nu = 0.3, where the physical value is m t^2 / 12).
//  * Time step: Table 2-1's quadrangular / triangular shell row, L_e / c_w with L_e = A / longest
//    side (triangles 2A / longest side) and c_w = sqrt(E / (rho (1 - nu^2))), on the current nodes
//    every cycle (fem::cfl), times sqrt of the element's density factor under mass scaling, times
//    a stability factor measured once per run. Why the factor: inside a regular mesh the highest
//    (membrane) frequency is exactly Table 2-1's 2 / dt, but free edges and corners, whose nodes
//    carry the mass of fewer elements, raise it: omega_max dt / 2 = 1.131 = sqrt(1 + nu) for a
//    single free element (its dilatation mode), 1.015 for a free 2 x 2 plate, 1.003 for 6 x 6
//    (tests/explicit/test_shell_bt.cpp, exact eigenvalues). 0.9 x Table 2-1 (Eq 2-27) is then
//    unstable for a lone element (the thesis's 2-element pallet is close). So, as the solver does
//    for solids, the group measures its omega_max at the start (Lanczos, Spectra, on its own
//    linearized stiffness against its own lumped masses, free: supports and the masses of other
//    parts only lower it) and multiplies its Table 2-1 steps by r = min(1, (2 / omega_max) /
//    smallest Table 2-1 step) (stability_factor(); 0.985 for a 2 x 2 plate, 1 when the Table step
//    is already a bound).
//  * State (history variables): per element the stresses of the three integration points and the
//    hourglass resultants (shellbt::State), and per node the positions and rotation matrices at
//    the last force evaluation (the step increments are taken against them). ElementGroup::
//    initialize resets all of it to the state the solver starts from.
//  * Stress output: von Mises at the bottom (z = -t/2, against the element normal of the node
//    numbering), mid-surface and top (z = +t/2) integration points; element_stress() is the largest
//    of the three (the part maxima the solver tracks), cell_fields() gives the three for VTU.
//  * Parallel: elements in chunks coloured so that chunks of one colour share no node (as
//    Hex8Group), each adding its forces and moments straight into the nodal arrays: the same bits
//    on any number of threads.
//
// Usage (a steel plate meshed in quad4, part "plate", 2 mm thick):
//   ExplicitModel model(mesh);
//   model.add_shells("plate", steel, {.thickness = 2e-3});
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "element/shell_bt_explicit.hpp"
#include "explicit/element_group.hpp"
#include "explicit/parallel.hpp"
#include "material/elastic.hpp"

namespace fem {

/// Options of a shell part (LS-DYNA *SECTION_SHELL ELFORM 2 + *HOURGLASS): thickness (required),
/// transverse shear factor, hourglass coefficients (shellbt::ShellSection).
using ShellOptions = shellbt::ShellSection;

/// A block of quad4 (Belytschko-Tsay) or tri3 (degenerate quadrilateral) shells, one material.
class ShellGroup final : public ElementGroup {
public:
    ShellGroup(const Mesh& mesh, int block, const ElasticMaterial& material, const ShellOptions& options);
    std::string kind() const override { return triangles_ ? "shell tri3" : "shell quad4"; }
    int size() const override { return static_cast<int>(conn_.size()); }
    bool needs_rotations() const override { return true; }
    std::vector<int> nodes() const override { return nodes_; }
    void initialize(const NodalState& s) override;
    double add_lumped_mass(NodalState& s) const override;
    double mass() const override;
    std::vector<double> reference_time_steps() const override { return ref_dt_; }
    void set_mass_scaling(std::vector<double> factor) override;
    GroupForceResult internal_forces(NodalState& s, bool compute_dt) override;
    /// The largest von Mises stress of the three integration points per element (block order).
    std::vector<double> element_stress() const override;
    /// "von_mises_bottom", "von_mises_mid", "von_mises_top" per element (block order).
    std::vector<std::pair<std::string, std::vector<double>>> cell_fields() const override;

    /// Von Mises stress of every element (block order) at integration point p (0 bottom, 1 mid,
    /// 2 top) at the last force evaluation.
    std::vector<double> surface_stress(int p) const;
    const ShellOptions& section() const { return section_; }
    const shellbt::Constants& constants() const { return consts_; }
    /// Element e's stored state (block order).
    const shellbt::State& state(int e) const { return state_[position_[e]]; }
    /// Element e's connectivity (triangles: the third node repeated as the fourth).
    const std::array<int, 4>& connectivity(int e) const { return conn_[e]; }
    /// Element e's lumped masses (unscaled).
    const shellbt::LumpedMass& lumped_mass(int e) const { return mass_[e]; }
    bool triangles() const { return triangles_; }
    /// Highest frequency of the group alone (free, its lumped masses with mass scaling, linear
    /// stiffness on the reference geometry) by Lanczos; the largest element frequency (each element
    /// alone, an upper bound) when Lanczos does not converge.
    double measure_omega_max() const;
    /// The factor on the Table 2-1 steps set by initialize() (1 before the first run).
    double stability_factor() const { return factor_; }

    static constexpr int kChunk = 512;

private:
    ElasticMaterial material_;
    ShellOptions section_;
    shellbt::Constants consts_;
    bool triangles_ = false;
    std::vector<std::array<int, 4>> conn_;   // block order
    std::vector<shellbt::LumpedMass> mass_;  // block order
    std::vector<double> ref_dt_, mass_scale_;
    double factor_ = 1.0;
    // Kernel order (elements sorted by their smallest node, par::node_order) and the position of
    // each block-order element in it.
    std::vector<int> order_, position_;
    std::vector<std::array<int, 4>> kconn_, klocal_;  // global and group-local node numbers
    std::vector<double> sqrt_mass_scale_;             // kernel order
    std::vector<shellbt::State> state_;               // kernel order
    std::vector<std::array<double, shellbt::kPoints>> vm_sq_;  // kernel order
    // The group's nodes (increasing) and per node (local index): position and rotation at the last
    // force evaluation, and this cycle's mid-step position and increments.
    std::vector<int> nodes_, local_;
    std::vector<Vec3> X_, x_prev_, x_mid_, du_, dtheta_;  // X_: reference positions
    std::vector<Mat3> R_prev_;
    par::ChunkColouring colouring_;
    struct Partial {
        double ie = 0, hg = 0, vm_sq = 0, dt = 0;
        int dt_k = -1, bad_k = -1;
    };
    std::vector<Partial> partial_;
};

}  // namespace fem
