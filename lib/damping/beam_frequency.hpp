#pragma once
// First natural frequency of a uniform Euler-Bernoulli cantilever carrying a point mass at its tip:
// Dunkerley's estimate (thesis Appendix E) and the exact root of the frequency equation.
namespace fem::damping {

struct CantileverTipMass {
    double youngs_modulus = 0.0;  // E, Pa
    double second_moment = 0.0;   // I, m^4
    double length = 0.0;          // L, m
    double beam_mass = 0.0;       // m = rho A L, kg
    double tip_mass = 0.0;        // M, kg (>= 0)
    /// Throws InputError naming the bad field.
    void validate() const;
};

/// I = pi d^4 / 64 (Eq E-3).
double circular_second_moment(double diameter);

struct DunkerleyEstimate {
    double omega_11 = 0.0;  // cantilever without tip mass: sqrt(3 EI / (0.243 m L^3))  (Eq E-2)
    double omega_22 = 0.0;  // massless cantilever with the tip mass: sqrt(3 EI / (M L^3))  (Eq E-2)
    double omega_1 = 0.0;   // Eq E-5 (the point mass has no rotary inertia, so Eq E-1's third term is 0)
};
/// Appendix E. Dunkerley's sum 1/omega_1^2 = sum 1/omega_ii^2 is a lower bound of the true omega_1.
DunkerleyEstimate dunkerley_cantilever_tip_mass(const CantileverTipMass& beam);

/// Exact first frequency: the smallest root lambda = beta L of
///   1 + cos(l) cosh(l) + mu l (cos(l) sinh(l) - sin(l) cosh(l)) = 0,  mu = M / m,
/// omega_1 = lambda^2 sqrt(EI / (m L^3)); solved with GSL's Brent root finder on (0, 1.8752].
double cantilever_tip_mass_first_frequency(const CantileverTipMass& beam);
/// The root lambda itself (1.8751 for M = 0).
double cantilever_tip_mass_eigenvalue(double mass_ratio);

}  // namespace fem::damping
