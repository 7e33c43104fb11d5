#pragma once
// The element groups the explicit solver knows today: 8-node hexahedra (one-point, hourglass
// control, neo-Hookean), corotational beams, and point masses. See element_group.hpp for the
// interface; element/hex8_explicit.hpp and element/beam_corotational.hpp for the formulations.
#include <array>
#include <vector>

#include "element/beam_corotational.hpp"
#include "element/hex8_explicit.hpp"
#include "explicit/element_group.hpp"
#include "explicit/parallel.hpp"
#include "material/elastic.hpp"

namespace fem {

/// Options of a solid part (LS-DYNA *SECTION_SOLID ELFORM 1 + *HOURGLASS + *CONTROL_BULK_VISCOSITY).
struct Hex8Options {
    double hourglass_qm = 0.1;        // QM of the stiffness hourglass control
    bool bulk_viscosity = true;       // Table 2-1 Q terms
    BulkViscosity bulk{};             // C0 = 1.5, C1 = 0.06
    double rayleigh_beta = 0.0;       // stiffness-proportional damping beta of Eq 2-39 [s]
};

/// A block of Hex8 elements, one material.
class Hex8Group final : public ElementGroup {
public:
    Hex8Group(const Mesh& mesh, int block, const ElasticMaterial& material, const Hex8Options& options = {});
    std::string kind() const override { return "hex8"; }
    int size() const override { return static_cast<int>(refs_.size()); }
    std::vector<int> nodes() const override { return nodes_; }
    double add_lumped_mass(NodalState& s) const override;
    double mass() const override;
    std::vector<double> reference_time_steps() const override;
    void set_mass_scaling(std::vector<double> factor) override;
    GroupForceResult internal_forces(NodalState& s, bool compute_dt) override;
    std::vector<double> element_stress() const override;
    /// Bulk viscosity and beta damping forces also go to NodalState::fv when the solver allocates it,
    /// so it books their work exactly (ElementGroup::adds_viscous_forces).
    bool adds_viscous_forces() const override {
        return kernel_material_.bulk_viscosity || kernel_material_.rayleigh_beta > 0.0;
    }
    double bulk_viscosity_linear() const override {
        return kernel_material_.bulk_viscosity ? kernel_material_.bulk.linear : 0.0;
    }

    const ElasticMaterial& material() const { return material_; }
    const hex8::Hex8Reference& reference(int e) const { return refs_[e]; }
    const std::array<int, 8>& connectivity(int e) const { return conn_[e]; }
    /// Number of colours of the element chunks (barriers per force evaluation on several threads).
    int colour_count() const { return static_cast<int>(colouring_.colours.size()); }

    /// Elements per chunk: the unit of the deterministic partition (energy partial sums, colouring).
    static constexpr int kChunk = 1024;

private:
    // Everything the public interface shows (element indices, connectivity(), reference(),
    // element_stress(), dt_element, bad_element) is in the block's element order. Each cycle works
    // in the kernel order instead: the elements sorted by their smallest node (par::node_order), so
    // that the nodal arrays are walked nearly sequentially and neighbouring elements, which share
    // nodes, are processed together (nodes loaded from memory about once per cycle).
    ElasticMaterial material_;
    hex8::Hex8Material kernel_material_;
    std::vector<std::array<int, 8>> conn_;    // block order
    std::vector<hex8::Hex8Reference> refs_;   // block order
    std::vector<int> nodes_;                  // the group's nodes, increasing
    std::vector<int> order_;                  // kernel position k -> element index (block order)
    std::vector<std::array<int, 8>> kconn_;   // connectivity in kernel order
    // The kernel's copy of refs_ (what each cycle streams), in kernel order, in blocks of
    // hex8::kLanes elements; the lanes of the last block past the end repeat the last element.
    std::vector<hex8::Hex8PackedBlock> packed_;
    std::vector<double> mass_scale_;       // density factor per element (1 = unscaled), block order
    std::vector<double> sqrt_mass_scale_;  // its square root (dt ~ sqrt(rho)), kernel order
    double dt_wave_speed_ = 0.0;           // Table 2-1 dilatational wave speed of the material
    std::vector<double> von_mises_sq_;     // squared von Mises stress, kernel order (sqrt on output)
    std::vector<double> ref_dt_;           // critical step per element on the reference geometry
    // Deterministic assembly: chunks of kChunk consecutive (kernel-order) elements, coloured so
    // that chunks of one colour share no node; each element adds its forces straight into the
    // nodal forces (see par::ChunkColouring).
    par::ChunkColouring colouring_;
    std::vector<ChunkSums> partial_;  // one per chunk (kept: no allocation per cycle)
};

/// Beam cross-section and orientation of a beam part (LS-DYNA *SECTION_BEAM).
struct BeamOptions {
    beam::Section section{};
    Vec3 orientation = Vec3::Zero();  // a vector in the local x-y plane (zero: automatic)
};

/// A block of Beam2 elements (corotational Euler-Bernoulli), one material. Its nodes get rotations.
class BeamGroup final : public ElementGroup {
public:
    BeamGroup(const Mesh& mesh, int block, const ElasticMaterial& material, const BeamOptions& options);
    std::string kind() const override { return "beam"; }
    int size() const override { return static_cast<int>(refs_.size()); }
    bool needs_rotations() const override { return true; }
    std::vector<int> nodes() const override;
    double add_lumped_mass(NodalState& s) const override;
    double mass() const override;
    std::vector<double> reference_time_steps() const override;
    void set_mass_scaling(std::vector<double> factor) override;
    GroupForceResult internal_forces(NodalState& s, bool compute_dt) override;
    std::vector<double> element_stress() const override { return stress_; }
    /// Ratio of the scaled to the physical rotational inertia of element e (see beam_corotational.hpp).
    double rotational_inertia_scaling(int e) const;
    /// "axial: Table 2-1 L/c" or "bending: transverse bound 2/omega" (stubby elements), on the
    /// reference length.
    std::string time_step_rule(int e) const override;

private:
    ElasticMaterial material_;
    BeamOptions options_;
    std::vector<std::array<int, 2>> conn_;
    std::vector<beam::Reference> refs_;
    // The kernel's data, blocks of hex8::kLanes elements (the lanes past the end repeat the last one).
    std::vector<beam::PackedBlock> packed_;
    std::vector<double> mass_scale_, sqrt_mass_scale_, stress_;
    std::vector<double> transverse_dt_;  // per element, on the reference length
    double wave_speed_ = 0.0;            // bar wave speed sqrt(E / rho)
};

/// Point masses (LS-DYNA *ELEMENT_MASS, thesis "Mass 166"): a mass (and optional isotropic
/// rotational inertia) on a node. No forces, no time step limit.
class PointMassGroup final : public ElementGroup {
public:
    PointMassGroup(std::string part, std::vector<int> nodes, std::vector<double> masses,
                   std::vector<double> rotational_inertia = {});
    std::string kind() const override { return "point mass"; }
    int size() const override { return static_cast<int>(nodes_.size()); }
    bool needs_rotations() const override { return has_rotation_; }
    std::vector<int> nodes() const override { return nodes_; }
    double add_lumped_mass(NodalState& s) const override;
    double mass() const override;
    std::vector<double> reference_time_steps() const override;
    void set_mass_scaling(std::vector<double>) override {}
    GroupForceResult internal_forces(NodalState&, bool) override { return {}; }
    std::vector<double> element_stress() const override { return std::vector<double>(nodes_.size(), 0.0); }

private:
    std::vector<int> nodes_;
    std::vector<double> masses_, inertia_;
    bool has_rotation_ = false;
};

}  // namespace fem
