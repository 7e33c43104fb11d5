#pragma once
// Nodes tied to a node that carries rotations, at a fixed offset, by penalty springs (LS-DYNA
// *CONSTRAINED_NODAL_RIGID_BODY / *CONTACT_TIED_NODES_TO_SURFACE_OFFSET in spirit): each tied node p
// is held at the point x_a + R_a (X_p - X_a) that moves rigidly with its anchor a (position x_a,
// nodal rotation R_a), e.g. the chicken's paws gripped by a shell shackle (thesis Sec 5.4.2: "J1 is
// fixed with the shackle"). The anchor takes the reaction and its moment about the anchor.
//
//   force on p:        f = -k (x_p - x_a - r) - c (v_p - v_a - omega_a x r),   r = R_a (X_p - X_a)
//   on the anchor:     -f, and the moment r x (-f)
//
// The spring stiffness k is chosen per tie from the two nodes' masses so that the tie's own
// frequency is `frequency` [Hz] (k = m_p (2 pi f)^2), well above the structural frequencies the
// tie should transmit and below the solver's step limit; the dashpot gives the tie a damping ratio
// `damping_ratio` (of its own frequency, on the tied node's mass). The provider reports a stable
// step (the anchor's translational and rotational inertia included: omega^2 = k/m_p + sum k / m_a
// + sum k |r|^2 / I_a, and the dashpot's damped bound) so the solver never steps past it. Its work is booked as "contact" energy
// (stored in the springs, dissipated in the dashpots).
//
// Two variants for the bird on its perch (thesis Sec 5.3, THESIS_CH4_5.md reconstruction 14: "J1
// nodes tied to the perch until 0.9 s, then released"):
// - the anchor may be a prescribed RigidMotion instead of a node (the perch, a rigid part carried
//   by the conveyor): each tied node is held at motion.position(X_p, t) with the dashpot on
//   v_p - motion.velocity(X_p, t); the motion takes the reaction (it is prescribed), so the step
//   bound is the tied node's own, omega^2 = k / m_p;
// - `release_time`: from that time on the ties exert nothing (the paws let go at the shackling
//   time). Their work up to then stays booked, so the energy balance holds across the release: the
//   energy the springs held is what they had taken out of the structure, and it stays taken out.
// - `engage_time` (motion anchors): the ties exert nothing before that time and then hold each node
//   at the point of the motion where the node is at that time (the material point X with
//   pose(t_e).position(X) = x_p(t_e)), e.g. the shackle's gripper taking the paws at the shackling
//   time (Sec 5.3: "the shackle ... grips both legs"). The node's velocity relative to that point
//   is then taken out by the dashpot and the spring within a few periods of the tie (~1 ms at 2 kHz
//   and a damping ratio 0.3): a gripper closing, not a rigid impact.
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "explicit/element_group.hpp"
#include "explicit/rigid_motion.hpp"

namespace fem {

struct OffsetTieOptions {
    double frequency = 2000.0;    // [Hz] each tie's frequency on its tied node's mass
    double damping_ratio = 0.3;   // of that frequency
    /// [s] the ties act for t < release_time and exert nothing from it on (default: never released).
    double release_time = std::numeric_limits<double>::infinity();
    /// [s] motion anchors only: the ties act from this time on, each node held where it is then
    /// (default: from the start, each node held where the motion carries its reference position).
    double engage_time = -std::numeric_limits<double>::infinity();
};

class OffsetTie final : public ForceProvider {
public:
    /// Ties each of `nodes` to anchors[i] (same length); anchors must carry rotations (shells,
    /// beams) when any offset is non-zero. InputError for mismatched lists or a node tied to itself.
    OffsetTie(std::string name, std::vector<int> nodes, std::vector<int> anchors, OffsetTieOptions options = {});
    /// Ties each of `nodes` to the point of the prescribed rigid `motion` that starts where the node
    /// starts (x_p held at motion.position(X_p, t)). InputError for an empty list or a node listed twice.
    OffsetTie(std::string name, std::vector<int> nodes, RigidMotion motion, OffsetTieOptions options = {});
    std::string name() const override { return name_; }
    void initialize(const NodalState& s) override;
    void add_forces(double t, const NodalState& s, std::vector<Vec3>& force, std::vector<Vec3>& moment) override;
    double stable_time_step(const NodalState& s) const override;
    /// Largest |x_p - x_a - r| over the ties at the last force evaluation [m] (how well the tie holds).
    double max_gap() const { return max_gap_; }
    /// Sum of the tie forces on the tied nodes at the last force evaluation [N] (the reaction).
    const Vec3& total_force() const { return total_force_; }
    /// Whether the ties have let go at time t (t >= options.release_time).
    bool released(double t) const { return t >= options_.release_time; }
    /// Whether the ties act at time t (engaged and not yet released).
    bool holding(double t) const { return t >= options_.engage_time && !released(t); }
    /// Restart: with an engage time, whether the ties have engaged and where they hold the nodes.
    void save_state(io::H5Writer& w, const std::string& prefix) const override;
    void restore_state(const io::H5Reader& r, const std::string& prefix) override;

private:
    std::string name_;
    std::vector<int> nodes_, anchors_;  // anchors_ empty when the anchor is `motion_`
    std::optional<RigidMotion> motion_;
    OffsetTieOptions options_;
    void check_options() const;
    /// An engage time was given: the held points are captured then (and are restart state).
    bool engages_late() const { return options_.engage_time > -std::numeric_limits<double>::infinity(); }
    std::vector<Vec3> offset_;        // X_p - X_a (reference); with a motion anchor X_p (after a late engagement: the held point)
    bool engaged_ = false;            // a late engagement has captured the held points
    std::vector<double> k_, c_;
    double dt_ = 0.0;
    double max_gap_ = 0.0;
    Vec3 total_force_ = Vec3::Zero();
};

}  // namespace fem
