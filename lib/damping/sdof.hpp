#pragma once
// The single-DOF viscously damped oscillator of thesis Sec 2.5.1 (Eq 2-40..2-43) and Appendix D:
// free response in all three regimes, the Laplace transfer function of Table 2-7, and the
// frequency response (receptance, magnification factor D_s of Eq D-18).
#include <cstddef>

#include "damping/signal.hpp"

namespace fem::damping {

/// u'' + 2 zeta omega_n u' + omega_n^2 u = 0 (Eq 2-40) with u(0) = x0, u'(0) = v0.
struct Sdof {
    double zeta = 0.0;     // damping ratio c / c_cr (Eq 2-43), >= 0
    double omega_n = 0.0;  // natural frequency sqrt(k/m) (Eq 2-41), rad/s, > 0
    double x0 = 0.0;       // initial displacement
    double v0 = 0.0;       // initial velocity

    /// Throws InputError naming the bad field (zeta < 0, omega_n <= 0, non-finite values).
    void validate() const;
    /// Damped frequency omega_n sqrt(1 - zeta^2) (0 when zeta >= 1).
    double omega_d() const;
    /// Displacement at time t >= 0: underdamped (zeta < 1), critically damped (zeta == 1) or
    /// overdamped (zeta > 1) closed form.
    double displacement(double t) const;
    /// Velocity at time t >= 0. The velocity obeys the same equation (2-40), with initial values
    /// v0 and u''(0) = -2 zeta omega_n v0 - omega_n^2 x0, so it is displacement() of that SDOF.
    double velocity(double t) const;
    /// The response sampled at t = i dt, i = 0..n-1.
    SampledSignal sample(double dt, std::size_t n) const;
};

/// Table 2-7: the Laplace transform of the free response,
///   X(s) = ((s + 2 zeta omega_n) x(0) + x'(0)) / (s^2 + 2 zeta omega_n s + omega_n^2)
///        = (b1 s + b0) / (s^2 + a1 s + a0).
struct SdofTransferFunction {
    double b1 = 0.0, b0 = 0.0;  // numerator: b1 = x(0), b0 = 2 zeta omega_n x(0) + x'(0)
    double a1 = 0.0, a0 = 0.0;  // denominator: a1 = 2 zeta omega_n, a0 = omega_n^2
};
SdofTransferFunction transfer_function(const Sdof& s);
/// The inverse: zeta, omega_n, x(0) and x'(0) from the four printed coefficients (a0 > 0).
Sdof sdof_from_transfer_function(const SdofTransferFunction& tf);

/// Eq D-18: magnification factor D_s = 1 / sqrt((1 - r^2)^2 + (2 zeta r)^2), r = omega / omega_n.
double magnification_factor(double r, double zeta);

/// Eq D-14: the two frequency ratios r1 < r2 where D_s = D_s(r = 1) / sqrt 2 (the thesis's
/// definition, Eq D-11, relative to the value at r = 1). r1 is NaN when it does not exist
/// (1 - 2 zeta^2 < 2 zeta sqrt(1 + zeta^2), zeta > 0.354).
struct HalfPowerRatios { double r1, r2; };
HalfPowerRatios half_power_ratios(double zeta);

/// What a measurement finds: the ratios where D_s = (its actual peak) / sqrt 2. The peak of D_s is
/// 1 / (2 zeta sqrt(1 - zeta^2)) at r = sqrt(1 - 2 zeta^2), and the two points solve
/// r^2 = 1 - 2 zeta^2 -+ 2 zeta sqrt(1 - zeta^2); r1 is NaN above zeta = sin(pi/8) = 0.383.
HalfPowerRatios peak_half_power_ratios(double zeta);

/// The damping ratio Eq D-17 returns on an exact receptance FRF of damping ratio zeta, with the
/// resonance peak r = sqrt(1 - 2 zeta^2) taken as omega_n: (r2 - r1) / (2 r_peak) from
/// peak_half_power_ratios. Equals zeta (1 + O(zeta^2)): the method's bias at large zeta.
double half_power_estimate(double zeta);

/// The largest zeta for which D_s has a resonance peak above r = 0: 1 / sqrt 2 (d D_s / d r = 0
/// at r = sqrt(1 - 2 zeta^2)).
double max_zeta_with_resonance_peak();

}  // namespace fem::damping
