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
    std::vector<int> nodes() const override { return scatter_.nodes; }
    double add_lumped_mass(NodalState& s) const override;
    double mass() const override;
    std::vector<double> reference_time_steps() const override;
    void set_mass_scaling(std::vector<double> factor) override;
    GroupForceResult internal_forces(NodalState& s, bool compute_dt) override;
    std::vector<double> element_stress() const override;

    const ElasticMaterial& material() const { return material_; }
    const hex8::Hex8Reference& reference(int e) const { return refs_[e]; }
    const std::array<int, 8>& connectivity(int e) const { return conn_[e]; }

private:
    ElasticMaterial material_;
    hex8::Hex8Material kernel_material_;
    std::vector<std::array<int, 8>> conn_;
    std::vector<hex8::Hex8Reference> refs_;
    // The kernel's copy of refs_ (what each cycle streams), in blocks of hex8::kLanes elements;
    // the lanes of the last block past the end repeat the last element (results discarded).
    std::vector<hex8::Hex8Packed4> packed_;
    std::vector<double> mass_scale_;   // density factor per element (1 = unscaled)
    std::vector<double> sqrt_mass_scale_;  // its square root (dt ~ sqrt(rho))
    double dt_wave_speed_ = 0.0;       // Table 2-1 dilatational wave speed of the material
    std::vector<double> von_mises_sq_; // squared von Mises stress per element (sqrt taken on output)
    std::vector<double> dt_;           // critical step per element at the last dt evaluation
    std::vector<double> ref_dt_;       // critical step per element on the reference geometry
    // Deterministic assembly: element forces go to fe_ (8 per element); each node then sums its
    // element slots in a fixed order (CSR node -> slots), whatever the number of threads.
    std::vector<Vec3> fe_;
    par::NodeScatter scatter_;  // the group's nodes and their element force slots
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

private:
    ElasticMaterial material_;
    BeamOptions options_;
    std::vector<std::array<int, 2>> conn_;
    std::vector<beam::Reference> refs_;
    std::vector<double> mass_scale_, stress_;
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
