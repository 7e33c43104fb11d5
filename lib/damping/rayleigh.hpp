#pragma once
// Rayleigh (proportional) damping, thesis Sec 2.5.1: [C] = alpha [M] + beta [K] (Eq 2-39). For a
// mode of natural frequency omega the damping ratio is zeta = (alpha / omega + beta omega) / 2
// (Eq 2-45): the mass term damps the low modes, the stiffness term the high ones (Fig 2-14).
namespace fem::damping {

/// The two scalars of Eq 2-39: alpha (1/s) multiplies the mass matrix, beta (s) the stiffness.
struct RayleighCoefficients {
    double alpha = 0.0;
    double beta = 0.0;
};

/// Eq 2-45: the damping ratio of a mode of natural frequency omega (rad/s, > 0).
double rayleigh_damping_ratio(const RayleighCoefficients& c, double omega);

/// Eq 2-46 and 2-47: alpha and beta that give damping ratio zeta1 at omega1 and zeta2 at omega2
/// (the two solutions of Eq 2-45 written twice). Requires 0 < omega1 != omega2.
RayleighCoefficients rayleigh_from_two_modes(double omega1, double zeta1, double omega2, double zeta2);

/// The frequency where Eq 2-45 is smallest (d zeta / d omega = 0): sqrt(alpha / beta), with
/// zeta_min = sqrt(alpha beta). Requires alpha > 0 and beta > 0.
double rayleigh_minimum_frequency(const RayleighCoefficients& c);

/// Mass-proportional damping of one mode (beta = 0): zeta = alpha / (2 omega), so the alpha that
/// gives damping ratio zeta is 2 zeta omega, and the critical alpha (zeta = 1) is 2 omega.
double mass_proportional_alpha(double zeta, double omega);

}  // namespace fem::damping
