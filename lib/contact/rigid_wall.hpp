#pragma once
// A fixed, frictionless, infinite planar rigid wall (LS-DYNA *RIGIDWALL_PLANAR with the penalty
// option PWSID / *RIGIDWALL_PLANAR_... with fric = 0): every slave node behind the plane point p,
// normal n (pointing to the side the nodes belong on) by less than the depth limit gets
//   f = -k g n,  g = n . (x - p) - offset < 0,  k = penalty_scale x the node's Eq 2-30 stiffness
// (ContactSurface::node_stiffness: a pair with a rigid master takes the deformable side's k,
// contact.hpp, so a node meets the same spring on this wall as on a rigid part's faces lying in the
// plane). No search, no projection: O(slave nodes) per cycle.
//
//   auto& wall = contact::add_rigid_wall(model, contact::PlanarWall("fingers on mirror-plane",
//       Vec3(0, 0, 0.184), -Vec3::UnitZ(), contact::ContactSurface::from_part(mesh, "finger", rubber)));
//
// LS-DYNA correspondence: *RIGIDWALL_PLANAR card 1 NSID = the slave surface's nodes, card 2 XT YT
// ZT = point, XH YH ZH = point + normal, FRIC = 0 (frictionless; LS-DYNA's default constraint is
// kinematic, this is the penalty variant with SLSFAC x the node's stiffness); WVEL/motion: fixed.
// depth plays the part of a finite wall's thickness: a node deeper than it (through the wall) is
// left alone, as a rigid part's faces with that depth limit would.
//
// The wall is fixed, so it does no work: the solver's "contact" energy (minus the work of the
// provider forces on the structure) equals the springs' stored energy up to the central difference
// rule's O(dt^2), and the stored energy is 1/2 sum k g^2 over the nodes in contact. Its stable-step
// bound is the rigid-master case of ContactInterface::stability_frequency_squared: max k / m over
// the slave nodes.
#include <span>
#include <string>
#include <vector>

#include "contact/surface.hpp"
#include "explicit/solver.hpp"

namespace fem::contact {

struct WallOptions {
    double penalty_scale = 0.1;  // LS-DYNA SLSFAC (as ContactOptions::penalty_scale)
    double depth = std::numeric_limits<double>::infinity();  // deepest penetration taken as contact [m]
};

class PlanarWall final : public ForceProvider {
public:
    /// point: a point of the plane; normal: towards the side the slave nodes belong on (normalized
    /// here); slave: a deformable surface (ContactSurface::from_part or merge) whose nodes the wall
    /// holds. InputError for a zero normal, a rigid or empty slave, penalty_scale <= 0 or depth <= 0.
    PlanarWall(std::string name, const Vec3& point, const Vec3& normal, ContactSurface slave, WallOptions options = {});

    std::string name() const override { return name_; }
    void initialize(const NodalState& s) override;
    void add_forces(double t, const NodalState& s, std::vector<Vec3>& force, std::vector<Vec3>& moment) override;
    double stable_time_step(const NodalState& s) const override;
    ContactReport contact_report() const override;
    void save_state(io::H5Writer& w, const std::string& prefix) const override;
    void restore_state(const io::H5Reader& r, const std::string& prefix) override;

    const Vec3& point() const { return point_; }
    const Vec3& normal() const { return normal_; }
    const ContactSurface& slave_surface() const { return slave_; }
    /// Signed distance of x from the plane along the normal (negative: behind the wall).
    double distance(const Vec3& x) const { return normal_.dot(x - point_); }
    /// Force the slave nodes exert on the wall in the last evaluation (the reaction; along -normal).
    const Vec3& force_on_wall() const { return force_on_wall_; }
    /// Slave nodes in contact in the last evaluation (mesh node numbers, in slave-surface order).
    const std::vector<int>& nodes_in_contact() const { return active_; }
    double stored_energy() const { return stored_; }
    /// Deepest penetration over all evaluations so far [m], and as a fraction of the node's local
    /// element size (ContactSurface::node_size; as ContactInterface's).
    double max_penetration() const { return max_penetration_; }
    double max_penetration_fraction() const { return max_penetration_fraction_; }
    /// Highest frequency squared the wall's springs add (max k / m over the slave nodes).
    double stability_frequency_squared(std::span<const double> mass) const;

private:
    std::string name_;
    Vec3 point_, normal_;
    ContactSurface slave_;
    WallOptions opt_;
    double w2_ = 0.0, stored_ = 0.0, max_penetration_ = 0.0, max_penetration_fraction_ = 0.0;
    Vec3 force_on_wall_ = Vec3::Zero();
    std::vector<int> active_;
};

/// Adds the wall to the model as a force provider; the returned reference stays valid for the
/// model's life.
PlanarWall& add_rigid_wall(ExplicitModel& model, PlanarWall wall);

}  // namespace fem::contact
