#pragma once
// Mass-proportional damping relative to a prescribed rigid motion: the damping of Eq 2-39 acting on
// the velocity a node has relative to a moving frame, not on its absolute velocity (LS-DYNA's
// *DAMPING_RELATIVE in spirit, which damps a part relative to a rigid body so that vibrations die
// out but the body's motion through space is not resisted).
//
// The solver's mass damping (ExplicitModel::set_mass_damping, *DAMPING_PART_MASS) puts -alpha m v on
// each node of the part. This provider adds, on the same nodes with the same alpha,
//
//     + alpha m v_frame(x),   v_frame(x) = v0(t) + omega(t) x x   (RigidPose::velocity_at)
//
// (and + alpha I omega(t) on the nodes that carry rotations), so that the net damping force is
// -alpha m (v - v_frame(x)): zero for a part that moves with the frame, the ordinary damping of
// Eq 2-39 for its motion relative to it. Uses: fingers damped in the frame of the turning drum
// (hand::DampingFrame::drum); the bird on the inverting shackle damped relative to the shackle's
// drive (chicken_shackling Step 4, a test of what the thesis's damping acted on). The solver books
// the provider's work with the force providers' ("contact") energy, so the energy balance holds.
//
// set_relative_mass_damping(model, part, alpha, frame) sets both halves on a part. A node the part
// shares with a part of another alpha is damped with the largest alpha by the solver (Eq 2-39's
// rule) and with this part's alpha by the frame term: give shared nodes one alpha.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "explicit/element_group.hpp"
#include "explicit/rigid_motion.hpp"

namespace fem {

class ExplicitModel;

class RelativeMassDamping final : public ForceProvider {
public:
    /// `node_alpha`: (node, alpha [1/s]) pairs, each node once, alpha >= 0 (InputError otherwise,
    /// naming `name`).
    RelativeMassDamping(std::string name, RigidMotion frame, std::vector<std::pair<int, double>> node_alpha);
    std::string name() const override { return name_; }
    void initialize(const NodalState& s) override;
    void add_forces(double t, const NodalState& s, std::vector<Vec3>& force, std::vector<Vec3>& moment) override;

private:
    std::string name_;
    RigidMotion frame_;
    std::vector<std::pair<int, double>> node_alpha_;
    std::vector<double> alpha_mass_;                 // alpha m per entry of node_alpha_
    std::vector<std::pair<int, double>> rotational_;  // (rotational slot, alpha I) of the nodes with rotations
};

/// Damps `part` at alpha [1/s] relative to `frame`: ExplicitModel::set_mass_damping(part, alpha) and a
/// RelativeMassDamping on the part's nodes, named "<part> damped relative to <frame_name>". Returns it.
RelativeMassDamping& set_relative_mass_damping(ExplicitModel& model, std::string_view part, double alpha, RigidMotion frame,
                                               std::string_view frame_name);

}  // namespace fem
