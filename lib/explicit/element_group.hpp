#pragma once
// The element interface of the explicit solver and the nodal state it acts on.
//
// An ElementGroup is one block of the mesh with one formulation and one material (LS-DYNA's
// *PART + *SECTION + *MAT). The solver only talks to this interface, so shells and tetrahedra join
// later by adding a group class: lumped mass, internal forces (with energies), the stable time
// step, and stresses for output.
//
// Nodal state: every node has translational DOFs. Nodes used by a group that needs rotations
// (beams; later shells) also get rotational DOFs: NodalState::rot_index[node] >= 0 then indexes
// the arrays of angular velocity, moment, rotational inertia and the nodal rotation matrix. Solid-
// only models carry no rotational storage.
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "mesh/mesh.hpp"

namespace fem {

namespace io {
class H5Writer;
class H5Reader;
}  // namespace io

struct NodalState {
    std::vector<Vec3> X;      // reference coordinates
    std::vector<Vec3> x;      // current coordinates (time n)
    std::vector<Vec3> v;      // velocities (time n - 1/2 during the force evaluation)
    std::vector<Vec3> f;      // internal (resisting) forces being accumulated
    std::vector<double> mass; // lumped translational mass
    // Rotational DOFs, only for nodes that need them.
    std::vector<int> rot_index;        // per node: -1, or the index into the arrays below
    std::vector<int> rot_node;         // per rotational slot: its node
    std::vector<Vec3> omega;           // angular velocity (global frame)
    std::vector<Vec3> moment;          // internal (resisting) moments being accumulated
    std::vector<double> inertia;       // isotropic lumped rotational inertia
    std::vector<Mat3> rotation;        // nodal triad relative to the reference
    // The viscous part of f (bulk viscosity, stiffness damping), per node. Allocated by the solver
    // only when some group books it (ElementGroup::adds_viscous_forces); empty otherwise, and then
    // no group writes it. The solver books its work like the mass damping (solver.cpp).
    std::vector<Vec3> fv;
    int node_count() const { return static_cast<int>(x.size()); }
    int rotational_count() const { return static_cast<int>(rot_node.size()); }
};

/// What one internal-force pass of a group returns (energies are totals over the group).
struct GroupForceResult {
    double internal_energy = 0.0;    // stored elastic energy (hyperelastic: exact state function)
    double hourglass_energy = 0.0;   // stored hourglass energy
    double viscous_power = 0.0;      // bulk viscosity + stiffness damping dissipation rate [W] at v(n-1/2)
    double dt_min = std::numeric_limits<double>::infinity();  // smallest critical step (unscaled by 0.9)
    int dt_element = -1;             // element that has it (index within the block)
    int bad_element = -1;            // first inverted / non-finite element, -1 when all fine
    double max_von_mises = 0.0;      // over the group (beams: outer-fibre stress)
};

/// What one chunk of a group's elements adds up during a force pass (groups run their chunks in
/// parallel, each into its own ChunkSums; elements indexed in the group's kernel order).
struct ChunkSums {
    double ie = 0, hg = 0, visc = 0, vm_sq = 0, dt = 0;  // energies, viscous power, max squared von Mises, min step
    int dt_k = -1, bad_k = -1;                           // kernel index of the step's element, first bad element

    /// Keeps element k's critical step when it is the smallest of the chunk so far.
    void take_step(double step, int k) {
        if (step < dt) {
            dt = step;
            dt_k = k;
        }
    }
};

/// An element's critical step 2/omega lowered by stiffness damping beta [s]:
/// dt (sqrt(1 + xi^2) - xi) with xi = beta omega / 2 = beta / dt (the damped central difference's bound).
inline double stiffness_damped_step(double dt, double beta) {
    if (beta <= 0.0) return dt;
    const double xi = beta / dt;
    return dt * (std::sqrt(1.0 + xi * xi) - xi);
}

/// The group's result from its chunks' sums, combined in the fixed chunk order (the same bits on
/// any number of threads); order maps kernel index -> element index within the block. Without
/// compute_dt the step is NaN (not computed this pass).
GroupForceResult combine_chunks(const std::vector<ChunkSums>& chunks, const std::vector<int>& order, bool compute_dt);

class ElementGroup {
public:
    virtual ~ElementGroup() = default;
    /// "hex8", "beam", "point mass": for messages and the summary.
    virtual std::string kind() const = 0;
    virtual int size() const = 0;
    /// True when the group's nodes need rotational DOFs.
    virtual bool needs_rotations() const { return false; }
    /// Nodes the group touches (for allocating rotational DOFs).
    virtual std::vector<int> nodes() const = 0;
    /// Called by the solver once at the start of a run, when the nodal state (positions, rotations)
    /// is set up and before the first force evaluation: a group with history variables (the stresses
    /// of a rate-form shell) resets them to this state. Stateless groups ignore it.
    virtual void initialize(const NodalState& s) {}
    /// Adds the group's lumped mass (and rotational inertia) to the state; returns the mass added
    /// by selective mass scaling (already included).
    virtual double add_lumped_mass(NodalState& s) const = 0;
    /// Physical mass of the group (without mass scaling).
    virtual double mass() const = 0;
    /// Critical steps of every element on the reference geometry (for mass scaling at start).
    virtual std::vector<double> reference_time_steps() const = 0;
    /// Multiplies element e's density by factor[e] (selective mass scaling, Sec 2.3.5 obs. 4).
    virtual void set_mass_scaling(std::vector<double> factor) = 0;
    /// Adds internal forces (and moments) at state.x / state.v to state.f (state.moment). When
    /// compute_dt, also evaluates every element's critical step on the current coordinates.
    /// Deterministic for any number of threads.
    virtual GroupForceResult internal_forces(NodalState& s, bool compute_dt) = 0;
    /// Per-element von Mises stress (beams: outer-fibre stress) at the last force evaluation.
    virtual std::vector<double> element_stress() const = 0;
    /// Which rule gives element e's critical step (the summary names it for the controlling element):
    /// "Table 2-1" unless the group has several (beams: axial L/c or the transverse bending bound).
    virtual std::string time_step_rule(int element) const { return "Table 2-1"; }
    /// Further per-element output fields for VTU (name, one value per element of the block), e.g.
    /// the shells' von Mises stress at the top and bottom surfaces. Blocks of other groups get zeros.
    virtual std::vector<std::pair<std::string, std::vector<double>>> cell_fields() const { return {}; }

    /// True when the group has viscous forces (bulk viscosity, stiffness damping) and, whenever
    /// s.fv is non-empty, internal_forces also adds their nodal values to s.fv (they stay in s.f).
    /// The solver then books their work exactly as the central-difference update does it (force at
    /// n times (v(n-1/2) + v(n+1/2))/2); for other groups it books viscous_power x dt (first order:
    /// a few % to tens of % off under strong bulk viscosity, tests/explicit).
    virtual bool adds_viscous_forces() const { return false; }
    /// C1, the linear coefficient of the bulk viscosity in the group's Table 2-1 step (Q = C1 c + ...);
    /// 0 when the group has no bulk viscosity. The solver's flat-hexahedron survey reads it
    /// (cfl::flat_hexahedron_step_factor).
    virtual double bulk_viscosity_linear() const { return 0.0; }
    /// Scales the group's critical steps by r (the solver's measured stability factor, <= 1),
    /// applied before any stiffness-damping reduction of the step. Returns false when the group
    /// does not support it: the solver then multiplies the step the group returns by r.
    virtual bool set_stability_factor(double r) { return false; }
    /// An upper bound on the group's contribution to omega_max without an eigen-solve of the whole
    /// model: the largest frequency of its elements, each alone with its lumped masses (element
    /// eigenvalue inequality, Irons; Hughes Sec 9.1.5). 0 when the group does not know one. Used
    /// only when the solver's Lanczos measurement does not converge.
    virtual double element_omega_bound() const { return 0.0; }

    /// Restart (ExplicitSolver dumps): the group's own state that a later cycle depends on (history
    /// variables such as plastic strains or incremental hourglass forces), written under the HDF5
    /// group `prefix` (ending in '/') and read back into a group built the same way. Not the nodal
    /// state, nor the forces of the last evaluation (the solver saves those). Today's groups keep
    /// none: hyperelastic, total-form hourglass control, so their forces follow from x and v alone.
    virtual void save_state(io::H5Writer& w, const std::string& prefix) const {}
    virtual void restore_state(const io::H5Reader& r, const std::string& prefix) {}

    std::string part;      // part name (from the block)
    int block = -1;        // block index in the mesh
};

/// What a contact force provider reports for the run summary (ForceProvider::contact_report).
struct ContactReport {
    bool is_contact = false;              // false: not a contact (nothing to report)
    double max_penetration = 0.0;         // deepest penetration over the run [m]
    double max_penetration_fraction = 0.0;  // deepest as a fraction of the slave's local element size
    double stored_energy = 0.0, dissipated_energy = 0.0;  // contact energy = stored + dissipated [J]
    // The last evaluation (what a study's observer samples every cycle: impulses, contact times):
    Vec3 force_on_master = Vec3::Zero();  // resultant force of the slave side on the master (a wall: on the wall) [N]
    int active = 0;                       // slave nodes in contact
};

/// State-dependent forces from outside the element groups (contact, couplings): the solver calls
/// add_forces every cycle after the internal forces and counts their work as the "contact" energy
/// of the balance (energy taken out of the structure: penalty springs + friction). Implementations
/// must be deterministic (fixed summation order).
class ForceProvider {
public:
    virtual ~ForceProvider() = default;
    virtual std::string name() const = 0;
    /// Called once before the first cycle (masses are set).
    virtual void initialize(const NodalState& s) {}
    /// Adds forces (per node) and moments (per rotational slot, s.rot_index) acting ON the structure
    /// at time t, state x(n), v(n-1/2).
    virtual void add_forces(double t, const NodalState& s, std::vector<Vec3>& force, std::vector<Vec3>& moment) = 0;
    /// A limit on the step (e.g. penalty springs); infinity when it imposes none.
    virtual double stable_time_step(const NodalState& s) const { return std::numeric_limits<double>::infinity(); }
    /// Of the wall time spent in add_forces so far, the part spent searching (contact: candidate
    /// lists); the solver's timing table reports the rest as contact forces.
    virtual double search_seconds() const { return 0.0; }
    /// Penetration and energy statistics for the run summary (contact interfaces).
    virtual ContactReport contact_report() const { return {}; }
    /// Nodal fields for the VTU output (name, one value per mesh node), e.g. contact pressure;
    /// fields of the same name from several providers are added.
    virtual std::vector<std::pair<std::string, std::vector<double>>> point_fields(const NodalState& s) const { return {}; }
    /// Restart: everything a later add_forces depends on (contact: friction springs and the segment
    /// each node sticks to, candidate lists and rebuild counters, energies), under the HDF5 group
    /// `prefix`; restore_state reads it into a provider built the same way and initialized, and
    /// throws InputError when it does not fit (surface sizes).
    virtual void save_state(io::H5Writer& w, const std::string& prefix) const {}
    virtual void restore_state(const io::H5Reader& r, const std::string& prefix) {}
};

}  // namespace fem
