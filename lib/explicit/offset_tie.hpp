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
#include <string>
#include <vector>

#include "explicit/element_group.hpp"

namespace fem {

struct OffsetTieOptions {
    double frequency = 2000.0;    // [Hz] each tie's frequency on its tied node's mass
    double damping_ratio = 0.3;   // of that frequency
};

class OffsetTie final : public ForceProvider {
public:
    /// Ties each of `nodes` to anchors[i] (same length); anchors must carry rotations (shells,
    /// beams) when any offset is non-zero. InputError for mismatched lists or a node tied to itself.
    OffsetTie(std::string name, std::vector<int> nodes, std::vector<int> anchors, OffsetTieOptions options = {});
    std::string name() const override { return name_; }
    void initialize(const NodalState& s) override;
    void add_forces(double t, const NodalState& s, std::vector<Vec3>& force, std::vector<Vec3>& moment) override;
    double stable_time_step(const NodalState& s) const override;
    /// Largest |x_p - x_a - r| over the ties at the last force evaluation [m] (how well the tie holds).
    double max_gap() const { return max_gap_; }
    /// Sum of the tie forces on the tied nodes at the last force evaluation [N] (the reaction).
    const Vec3& total_force() const { return total_force_; }

private:
    std::string name_;
    std::vector<int> nodes_, anchors_;
    OffsetTieOptions options_;
    std::vector<Vec3> offset_;        // X_p - X_a (reference)
    std::vector<double> k_, c_;
    double dt_ = 0.0;
    double max_gap_ = 0.0;
    Vec3 total_force_ = Vec3::Zero();
};

}  // namespace fem
