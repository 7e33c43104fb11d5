#include "damping/rayleigh.hpp"

#include <cmath>
#include <fmt/format.h>

#include "core/error.hpp"

namespace fem::damping {

namespace {
void require_frequency(double omega, const char* name) {
    if (!(omega > 0.0) || !std::isfinite(omega))
        throw InputError(fmt::format("Rayleigh damping: {} = {} rad/s must be positive and finite", name, omega));
}
}  // namespace

double rayleigh_damping_ratio(const RayleighCoefficients& c, double omega) {
    require_frequency(omega, "omega");
    return 0.5 * (c.alpha / omega + c.beta * omega);  // Eq 2-45
}

RayleighCoefficients rayleigh_from_two_modes(double omega1, double zeta1, double omega2, double zeta2) {
    require_frequency(omega1, "omega1");
    require_frequency(omega2, "omega2");
    if (omega1 == omega2)
        throw InputError(fmt::format("Rayleigh damping: the two frequencies must differ (both {} rad/s)", omega1));
    const double d = omega2 * omega2 - omega1 * omega1;
    return {2.0 * omega1 * omega2 * (zeta1 * omega2 - zeta2 * omega1) / d,  // Eq 2-46
            2.0 * (zeta2 * omega2 - zeta1 * omega1) / d};                      // Eq 2-47
}

double rayleigh_minimum_frequency(const RayleighCoefficients& c) {
    if (!(c.alpha > 0.0) || !(c.beta > 0.0))
        throw InputError(fmt::format("Rayleigh damping: the minimum of Eq 2-45 needs alpha > 0 and beta > 0 "
                                     "(alpha = {}, beta = {})", c.alpha, c.beta));
    return std::sqrt(c.alpha / c.beta);
}

double mass_proportional_alpha(double zeta, double omega) {
    require_frequency(omega, "omega");
    return 2.0 * zeta * omega;  // Eq 2-45 with beta = 0, solved for alpha
}

}  // namespace fem::damping
