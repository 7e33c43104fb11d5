#include "damping/beam_frequency.hpp"

#include <cmath>
#include <fmt/format.h>
#include <memory>
#include <numbers>

#include <gsl/gsl_roots.h>

#include "core/error.hpp"
#include "damping/gsl_guard.hpp"

namespace fem::damping {

void CantileverTipMass::validate() const {
    auto positive = [](double v, const char* name) {
        if (!(v > 0.0) || !std::isfinite(v)) throw InputError(fmt::format("cantilever with tip mass: {} = {} must be > 0", name, v));
    };
    positive(youngs_modulus, "Young's modulus E");
    positive(second_moment, "second moment of area I");
    positive(length, "length L");
    positive(beam_mass, "beam mass m");
    if (!(tip_mass >= 0.0) || !std::isfinite(tip_mass))
        throw InputError(fmt::format("cantilever with tip mass: tip mass M = {} must be >= 0", tip_mass));
}

double circular_second_moment(double diameter) {
    if (!(diameter > 0.0)) throw InputError(fmt::format("circular section: diameter = {} must be > 0", diameter));
    return std::numbers::pi * std::pow(diameter, 4) / 64.0;  // Eq E-3
}

DunkerleyEstimate dunkerley_cantilever_tip_mass(const CantileverTipMass& b) {
    b.validate();
    const double EI = b.youngs_modulus * b.second_moment, L3 = std::pow(b.length, 3);
    DunkerleyEstimate d;
    // Eq E-2. 0.243 = 3 / 3.516^2: the factor that makes a tip-loaded spring 3EI/L^3 with an
    // effective mass 0.243 m reproduce the exact first cantilever frequency 3.516 sqrt(EI / (m L^3)).
    d.omega_11 = std::sqrt(3.0 * EI / (0.243 * b.beam_mass * L3));
    const double inv_sq = 1.0 / (d.omega_11 * d.omega_11) + b.tip_mass * L3 / (3.0 * EI);  // Eq E-1 (1/omega_22^2)
    d.omega_22 = b.tip_mass > 0.0 ? std::sqrt(3.0 * EI / (b.tip_mass * L3)) : INFINITY;
    d.omega_1 = 1.0 / std::sqrt(inv_sq);  // Eq E-5
    return d;
}

double cantilever_tip_mass_eigenvalue(double mass_ratio) {
    if (!(mass_ratio >= 0.0) || !std::isfinite(mass_ratio))
        throw InputError(fmt::format("cantilever with tip mass: mass ratio M/m = {} must be >= 0", mass_ratio));
    // f(0) = 2 > 0; at 1.8752 (just past the bare cantilever's root 1.87510) f < 0 for every mu >= 0,
    // and the first root moves down as the tip mass grows: the bracket (0, 1.8752] holds it.
    const double mu = mass_ratio;
    detail::GslCallback F([mu](double l) {
        return 1.0 + std::cos(l) * std::cosh(l) + mu * l * (std::cos(l) * std::sinh(l) - std::sin(l) * std::cosh(l));
    });
    detail::GslErrorsOff guard;
    std::unique_ptr<gsl_root_fsolver, decltype(&gsl_root_fsolver_free)> s(
        gsl_root_fsolver_alloc(gsl_root_fsolver_brent), gsl_root_fsolver_free);
    if (gsl_root_fsolver_set(s.get(), F.get(), 1e-6, 1.8752) != GSL_SUCCESS)
        throw SolverError(fmt::format("cantilever with tip mass: first root not bracketed for M/m = {}", mass_ratio));
    for (int it = 0; it < 200; ++it) {
        gsl_root_fsolver_iterate(s.get());
        if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s.get()), gsl_root_fsolver_x_upper(s.get()), 0.0, 1e-14) ==
            GSL_SUCCESS)
            break;
    }
    return gsl_root_fsolver_root(s.get());
}

double cantilever_tip_mass_first_frequency(const CantileverTipMass& b) {
    b.validate();
    const double l = cantilever_tip_mass_eigenvalue(b.tip_mass / b.beam_mass);
    return l * l * std::sqrt(b.youngs_modulus * b.second_moment / (b.beam_mass * std::pow(b.length, 3)));
}

}  // namespace fem::damping
