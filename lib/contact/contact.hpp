#pragma once
// Penalty node-to-segment contact with Coulomb friction (thesis Sec 2.3.6-2.3.7, after LS-DYNA's
// penalty method [Hallquist 1998]).
//
// Each slave node is checked against the master segments its candidate list (search.hpp) names.
// A segment is admissible when
//   - the gap of Eq 2-29 is negative (beyond round-off) and not deeper than the depth limit, and
//   - the node projects onto the segment (tangential offset within edge_tolerance x segment size).
// The node keeps the segment of the previous cycle while it stays admissible, else takes the
// admissible one whose closest point is nearest. Outside veto: when the node lies in front of a
// candidate face it projects onto, closer than its penetration, it is outside the master body (it
// only fell within the edge tolerance of a far face) and gets no force.
// The normal force f_n = -k g_n (Eq 2-30) acts on the slave node along the master normal, with
// k = penalty_scale x min(k of the slave node, k of the master segment) (Eq 2-30 on each side,
// including its s_f; the softer side governs, so a rubber node on an aluminium face is as stiff as
// the rubber). penalty_scale is LS-DYNA's SLSFAC (*CONTROL_CONTACT, default 0.1), which LS-DYNA
// multiplies into every SOFT=0 penalty stiffness on top of the thesis's s_f (= SFS, default 1):
// with 1.0 the contact springs of two hexahedral bars (nu = 0, two-way) made the central
// difference step of 0.9 x Table 2-1 unstable (test TwoEqualBars...), as LS-DYNA warns. The friction force follows friction.hpp. The opposite force goes to the master
// nodes weighted by the segment shape functions at the contact point, so the pair's forces sum to
// zero (momentum conserved exactly) and their moments about any point cancel up to the gap.
// A rigid master (ContactSurface::rigid_part: the surface of a rigid part of the explicit model, whose
// nodes the solver moves by the part's RigidMotion) receives no nodal forces: the reaction is summed
// into force_on_master() and moment_on_master().
// two_way (symmetric contact, deformable pairs only): a second pass with the roles swapped, so
// neither surface's nodes pass through the other's faces.
//
// Energy (for the energy balance): stored = sum 1/2 k g^2 + |f_t|^2 / (2 k) over active nodes (a
// state function like the strain energy), dissipated = accumulated friction dissipation, and
// rigid_work = work done on the deformable bodies by moving rigid masters (it belongs with the
// external work).
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "contact/friction.hpp"
#include "contact/projection.hpp"
#include "contact/search.hpp"
#include "contact/surface.hpp"

namespace fem::contact {

struct ContactOptions {
    FrictionLaw friction;            // Eq 2-34, 2-35 (default frictionless)
    double penalty_scale = 0.1;      // LS-DYNA SLSFAC: multiplies the Eq 2-30 stiffness (see above)
    bool two_way = false;            // symmetric: also the master's nodes against the slave's faces
    double margin = 0.0;             // search margin [m]; 0: 0.25 x mean master segment size
    int max_rebuild_interval = 100;  // cycles between forced rebuilds of the candidate lists
    double edge_tolerance = 0.05;    // projection may fall this fraction of the segment size outside it
    // Project a node only onto the candidates that can matter this cycle: the segment it was on (kept
    // while admissible), and the others only where their box (projection.hpp SegmentBox) does not
    // rule out a capture or an outside veto. The same forces to the last bit as projecting every
    // candidate (false: the reference, for tests).
    bool skip_far_candidates = true;
    // Capture only nodes that reached the master surface from in front (one-sided master faces, e.g.
    // a rigid plate; a shell with thickness has its own side rule). Each slave node remembers the
    // side it was last seen on: in front (it projected onto a face from in front, or was in
    // contact), or behind (first seen behind a face it projects onto without being captured, or
    // beside every face and behind the nearest one's plane: it came round an edge or fell past one).
    // A node seen behind is not captured, whatever its depth, until it is in front again; a node not
    // yet seen near a face follows the depth rule alone. So the depth limit can be the master's real
    // thickness: a node that enters a thin plate's outline from behind its edge (a leg crossing the
    // plane of a shackle plate) is not shot up by the penalty spring, and a node pressed into the
    // plate is held up to that depth (deeper it is let go, and taken again if it comes back within
    // it while still under the face: it came from in front). Every candidate is projected (skip_far_candidates does not
    // apply). InputError for a master with two-sided segments.
    bool track_approach_side = false;
};

/// An active contact: slave node `node` against master segment `segment` of the pass (`pass` 0:
/// slave surface nodes on master faces; 1: the two-way pass).
struct ContactPoint {
    int node = -1, segment = -1, pass = 0;
    Vec3 position = Vec3::Zero();     // the slave node's position
    Vec3 point = Vec3::Zero();        // the contact point on the master segment
    Vec3 normal = Vec3::UnitZ();      // master normal
    double gap = 0.0;                 // < 0
    double normal_force = 0.0;        // f_n of Eq 2-30 (>= 0)
    Vec3 tangential_force = Vec3::Zero();
    bool slipping = false;
};

class ContactInterface {
public:
    /// Deformable slave nodes against the master's faces, deformable (ContactSurface::from_part) or
    /// rigid (ContactSurface::rigid_part); node numbers: the mesh's.
    ContactInterface(std::string name, ContactSurface slave, ContactSurface master, ContactOptions options = {});
    ~ContactInterface();
    ContactInterface(ContactInterface&&) noexcept;

    /// One contact evaluation at positions x (all mesh nodes) at time t. v: velocities over the last
    /// cycle (x moved by v dt), used for the friction slip increment (dt = 0 at the start). Adds the
    /// contact forces acting on the nodes to `force` (same size as x).
    void evaluate(std::span<const Vec3> x, std::span<const Vec3> v, double t, double dt, std::span<Vec3> force);

    const std::string& name() const { return name_; }
    double stored_energy() const { return stored_; }
    double dissipated_energy() const { return dissipated_; }
    /// stored + dissipated: the "contact" term of the energy balance.
    double energy() const { return stored_ + dissipated_; }
    /// Work done by moving rigid masters on the deformable bodies (trapezoidal in time).
    double rigid_work() const { return rigid_work_; }
    /// Resultant contact force exerted on the master side by the slave side (pass 0 and 1).
    const Vec3& force_on_master() const { return f_master_; }
    /// Its moment about `about` (for a rigid master: the reaction a transducer measures).
    Vec3 moment_on_master(const Vec3& about) const { return m_master_ - about.cross(f_master_); }
    const std::vector<ContactPoint>& contacts() const { return points_; }
    /// Contact pressure [Pa] per mesh node at positions x (the last evaluation's contacts): each
    /// contact's normal force over the node's tributary area on its own surface projected on the
    /// contact normal (a quarter of each quadrilateral face around it, a third of each triangle, times
    /// |n_face . n|: the faces at right angles to the contact bear nothing); 0 where no contact.
    std::vector<double> nodal_pressure(std::span<const Vec3> x) const;
    /// True when the master is a rigid part.
    bool rigid_master() const { return master_->rigid; }
    /// Deepest penetration over all evaluations so far [m], and the deepest as a fraction of the slave
    /// node's local element size (ContactSurface::node_size; the two maxima need not be one node's).
    double max_penetration() const { return max_penetration_; }
    double max_penetration_fraction() const { return max_penetration_fraction_; }
    /// Wall time spent in the candidate search (CandidateList::update) over all evaluations [s].
    double search_seconds() const { return search_s_; }
    /// Node-to-segment projections made over all evaluations (ContactOptions::skip_far_candidates
    /// saves most of them).
    long projections() const { return projections_; }
    /// The surfaces: pass 0's slave nodes lie on slave_surface(), its master segments on
    /// master_surface(); pass 1 (two-way) swaps them.
    const ContactSurface& slave_surface() const { return *slave_; }
    const ContactSurface& master_surface() const { return *master_; }
    /// Highest frequency squared [1/s^2] the penalty springs can add to the mesh, for the time step
    /// (Weyl: omega_max^2(elements + contact) <= omega_e^2 + this, so dt <= 2 / sqrt(omega_e^2 +
    /// this)). Bound used: max over every slave node of k (1/m_slave + 1/m_lightest master node of
    /// the pass), k the largest stiffness the node can get (penalty_scale x the smaller of its own
    /// Eq 2-30 value and the stiffest master segment's),
    /// times the number of passes (two-way: a node is spring-loaded by both passes). Exact for one
    /// node on a rigid face; for a master node loaded by several slave nodes it assumes a master
    /// mesh no finer than the slave's. mass: lumped nodal masses of the model.
    double stability_frequency_squared(std::span<const double> mass) const;
    /// Search statistics: candidate-list rebuilds and cycles of pass 0.
    long rebuilds() const;
    long cycles() const;
    /// Restart: everything a later evaluate depends on (per pass the candidate lists, counters and
    /// rebuild positions, each slave node's friction spring force, segment, and on a two-sided
    /// (shell) face the side it touches and the contact normal), the energies and statistics, and the
    /// last evaluation's outputs, under the HDF5 group `prefix`. restore_state throws InputError when
    /// the file's surfaces differ in size from this interface's, or when a file without the sides
    /// (written before they were saved) has a node in contact with a two-sided face.
    void save_state(io::H5Writer& w, const std::string& prefix) const;
    void restore_state(const io::H5Reader& r, const std::string& prefix);

private:
    struct Pass;
    void check(std::span<const Vec3> x) const;
    void validate_options() const;
    std::string name_;
    ContactOptions opt_;
    // On the heap: the passes point at them, and the interface is moved into the model.
    std::unique_ptr<ContactSurface> slave_, master_;
    std::vector<std::unique_ptr<Pass>> passes_;
    double stored_ = 0.0, dissipated_ = 0.0, rigid_work_ = 0.0, rigid_power_ = 0.0;
    double max_penetration_ = 0.0, max_penetration_fraction_ = 0.0, search_s_ = 0.0;
    long projections_ = 0;
    Vec3 f_master_ = Vec3::Zero(), m_master_ = Vec3::Zero();
    std::vector<ContactPoint> points_;
};

/// Resultant force and moment (about `about`) of nodal forces `f` over `nodes`; with f the net
/// internal-minus-external force of constrained nodes this is the support reaction.
struct Resultant {
    Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
};
Resultant resultant(std::span<const int> nodes, std::span<const Vec3> f, std::span<const Vec3> x, const Vec3& about);

}  // namespace fem::contact
