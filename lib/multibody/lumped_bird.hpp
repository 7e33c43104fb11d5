#pragma once
// The two-dimensional lumped-parameter rigid-body model of the shackled bird that thesis Sec 5.4.2
// compares its FE results with ("Lagrange dynamics [Wang, 2009]", Figs 5-23..5-25). The thesis
// prints neither its equations nor its parameters; this is our reconstruction (shared/THESIS_CH4_5.md
// Sec 8), a planar pseudo-rigid-body chain driven at its base:
//
//   link 1   the shank L1 from the paw J1 (held by the shackle) to the joint J2: mass m1, centre of
//            mass c1 from J1, inertia I1 about it, absolute angle phi1 (from +X, counter-clockwise);
//   link 2   everything above J2 (L2, the body, neck and head) as one rigid body: mass m2, centre of
//            mass G2 at l2 from J2 in the direction phi2, inertia I2 about G2;
//   springs  k1 at J1 on phi1 - psi - rest1 (psi: the shackle's rotation) and k2 at J2 on
//            phi2 - phi1 - rest2 (pseudo-rigid-body springs standing for the compliant joints);
//   gravity  -g along Y;
//   damping  LS-DYNA's mass-proportional damping on absolute velocities (Eq 2-39, the FE chicken's
//            alpha = 100 1/s of Table 5-8): Rayleigh function D = alpha T, T the kinetic energy.
//
// With G1 = b + c1 e(phi1), G2 = b + L1 e(phi1) + l2 e(phi2), e(p) = (cos p, sin p),
// e'(p) = (-sin p, cos p) and the base b(t) (the paw, moving with the shackle), Lagrange's equations
// d/dt dT/dq' - dT/dq + dV/dq = -dD/dq' give M(q) q'' = Q:
//   M11 = I1 + m1 c1^2 + m2 L1^2,  M22 = I2 + m2 l2^2,  M12 = m2 L1 l2 cos(phi2 - phi1);
//   Q1 =  m2 L1 l2 sin(phi2 - phi1) phi2'^2 - s1 e'(phi1).(b'' + g Y) - k1 (phi1 - psi - rest1)
//         + k2 (phi2 - phi1 - rest2) - alpha (M11 phi1' + M12 phi2' + s1 e'(phi1).b'),
//   Q2 = -m2 L1 l2 sin(phi2 - phi1) phi1'^2 - s2 e'(phi2).(b'' + g Y) - k2 (phi2 - phi1 - rest2)
//         - alpha (M12 phi1' + M22 phi2' + s2 e'(phi2).b'),
//   s1 = m1 c1 + m2 L1,  s2 = m2 l2.
// The base moves as a rigid shackle: between switch times its pivot translates at a constant
// velocity and it turns at a constant rate about the pivot (the step profiles of Table 5-8). At a
// switch b' jumps by Db'; the chain's velocities jump by the impulse equations M Dq' = -(s1 e'(phi1),
// s2 e'(phi2)).Db' (the springs, gravity and damping are finite and give no impulse).
//
// Integrated with GSL's gsl_odeiv2 (Runge-Kutta-Prince-Dormand 8(9), adaptive, tolerances in
// LumpedBirdOptions).
#include <functional>
#include <vector>

#include "core/types.hpp"

namespace fem::multibody {

/// The chain's parameters (SI; angles in radians).
struct LumpedBird {
    double m1 = 0.0, c1 = 0.0, I1 = 0.0, L1 = 0.0;  // link 1 (the shank)
    double m2 = 0.0, l2 = 0.0, I2 = 0.0;            // link 2 (the rest of the bird)
    double k1 = 0.0, k2 = 0.0;                      // joint springs [N m / rad]
    double rest1 = 0.0, rest2 = 0.0;                // spring rest angles [rad]
    double alpha = 0.0;                             // mass damping [1/s]
    double g = 9.81;                                // gravity [m/s^2] along -Y
    /// A body point rigidly attached to link 2, given by where it is when link 2 is at phi2_ref
    /// with J2 at the origin (e.g. the body ellipsoid's centre, whose displacement Figs 5-24/5-25
    /// show).
    Vec2 body_point{0.0, 0.0};
    double phi2_ref = 0.0;

    /// Throws InputError naming the field (negative masses or springs, a singular mass matrix).
    void validate() const;
};

/// The shackle's rigid planar motion: from time `times[k]` on (times[0] = 0), its pivot translates at
/// `pivot_velocity[k]` and it turns at `rate[k]` (counter-clockwise) about the pivot. The paw J1 is
/// a point of the shackle: b(t) = P(t) + R(psi(t)) (b0 - P0).
struct ShackleMotion {
    Vec2 pivot0{0.0, 0.0};
    Vec2 paw0{0.0, 0.0};                  // b0: the paw at t = 0
    std::vector<double> times{0.0};
    std::vector<Vec2> pivot_velocity{Vec2(0.0, 0.0)};
    std::vector<double> rate{0.0};

    /// The motion held still.
    static ShackleMotion fixed(const Vec2& paw);
    /// A translation of the paw at `velocity` during [0, duration), then stopped.
    static ShackleMotion translation_step(const Vec2& paw, const Vec2& velocity, double duration);
    /// A rotation about `pivot` at `rate` during [0, duration), then stopped.
    static ShackleMotion rotation_step(const Vec2& paw, const Vec2& pivot, double rate, double duration);

    void validate() const;
    int segment(double t) const;   // the segment that holds t (jumps belong to the later one)
    double angle(double t) const;  // psi(t)
    Vec2 pivot(double t) const;
    Vec2 position(double t) const;      // b(t)
    Vec2 velocity(double t) const;      // b'(t) (the later segment's value at a switch)
    Vec2 acceleration(double t) const;  // b''(t) within a segment: the centripetal part
};

struct LumpedBirdState {
    double t = 0.0;
    double phi1 = 0.0, phi2 = 0.0, dphi1 = 0.0, dphi2 = 0.0;
};

struct LumpedBirdOptions {
    double abs_tolerance = 1e-10, rel_tolerance = 1e-10;  // GSL's error control on (phi, phi')
    double output_interval = 1e-3;                        // history sampling [s]
};

/// One sample of a run.
struct LumpedBirdSample {
    LumpedBirdState state;
    Vec2 paw;           // b(t)
    Vec2 joint2;        // J2
    Vec2 body_point;    // the attached body point (LumpedBird::body_point)
    double kinetic = 0.0, potential = 0.0;  // T (absolute velocities) and V (gravity + springs)
};

class LumpedBirdModel {
public:
    LumpedBirdModel(LumpedBird bird, ShackleMotion motion);
    const LumpedBird& bird() const { return bird_; }
    const ShackleMotion& motion() const { return motion_; }

    /// Accelerations (phi1'', phi2'') at state s.
    Vec2 accelerations(const LumpedBirdState& s) const;
    /// Mass matrix M(q) (2 x 2).
    Eigen::Matrix2d mass_matrix(const LumpedBirdState& s) const;
    double kinetic_energy(const LumpedBirdState& s) const;
    double potential_energy(const LumpedBirdState& s) const;
    LumpedBirdSample sample(const LumpedBirdState& s) const;

    /// The static equilibrium under gravity and the springs with the shackle as at time t (found by
    /// a heavily damped run to rest, then Newton on dV/dq = 0); throws SolverError when it is not a
    /// stable one (the Hessian of V not positive definite). `guess` starts the search.
    LumpedBirdState equilibrium(double t, const LumpedBirdState& guess) const;
    /// The linearised free vibration about a static equilibrium: squared circular frequencies, the
    /// eigenvalues of (K, M) with K the Hessian of V, ascending.
    Vec2 linearised_omega_squared(const LumpedBirdState& equilibrium) const;
    /// The corresponding mode shapes (columns, M-normalised), in (phi1, phi2).
    Eigen::Matrix2d linearised_modes(const LumpedBirdState& equilibrium) const;

    /// Integrates from `start` to `end_time`, sampling every options.output_interval (and at every
    /// switch of the shackle's motion, where the velocities jump).
    std::vector<LumpedBirdSample> run(const LumpedBirdState& start, double end_time, const LumpedBirdOptions& options = {}) const;

private:
    LumpedBird bird_;
    ShackleMotion motion_;
};

}  // namespace fem::multibody
