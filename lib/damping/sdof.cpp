#include "damping/sdof.hpp"

#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "core/error.hpp"

namespace fem::damping {

void Sdof::validate() const {
    if (!(zeta >= 0.0) || !std::isfinite(zeta)) throw InputError(fmt::format("SDOF model: damping ratio zeta = {} must be >= 0", zeta));
    if (!(omega_n > 0.0) || !std::isfinite(omega_n))
        throw InputError(fmt::format("SDOF model: natural frequency omega_n = {} rad/s must be > 0", omega_n));
    if (!std::isfinite(x0) || !std::isfinite(v0)) throw InputError(fmt::format("SDOF model: initial state x0 = {}, v0 = {} is not finite", x0, v0));
}

double Sdof::omega_d() const { return zeta < 1.0 ? omega_n * std::sqrt(1.0 - zeta * zeta) : 0.0; }

double Sdof::displacement(double t) const {
    const double sigma = zeta * omega_n;  // decay rate of the envelope
    const double b = v0 + sigma * x0;     // the same for all three regimes: x' + sigma x at t = 0
    if (zeta < 1.0) {
        // Underdamped: e^{-sigma t} (x0 cos wd t + (v0 + sigma x0) / wd sin wd t).
        const double wd = omega_d();
        return std::exp(-sigma * t) * (x0 * std::cos(wd * t) + b * std::sin(wd * t) / wd);
    }
    if (zeta == 1.0) return std::exp(-omega_n * t) * (x0 + b * t);  // critically damped
    // Overdamped: e^{-sigma t} (x0 cosh g t + (v0 + sigma x0) / g sinh g t), g = omega_n sqrt(zeta^2 - 1);
    // written with the two real exponentials once g t is large, where cosh and sinh would overflow.
    const double g = omega_n * std::sqrt(zeta * zeta - 1.0);
    if (g * t < 20.0) return std::exp(-sigma * t) * (x0 * std::cosh(g * t) + b * std::sinh(g * t) / g);
    return 0.5 * ((x0 + b / g) * std::exp((g - sigma) * t) + (x0 - b / g) * std::exp(-(g + sigma) * t));
}

double Sdof::velocity(double t) const {
    const double a0 = -2.0 * zeta * omega_n * v0 - omega_n * omega_n * x0;  // Eq 2-40 at t = 0
    return Sdof{zeta, omega_n, v0, a0}.displacement(t);
}

SampledSignal Sdof::sample(double dt, std::size_t n) const {
    validate();
    if (!(dt > 0.0)) throw InputError(fmt::format("SDOF model: sampling interval dt = {} must be > 0", dt));
    SampledSignal s{0.0, dt, std::vector<double>(n)};
    for (std::size_t i = 0; i < n; ++i) s.x[i] = displacement(s.time(i));
    return s;
}

SdofTransferFunction transfer_function(const Sdof& s) {
    s.validate();
    const double a1 = 2.0 * s.zeta * s.omega_n;  // Table 2-7 denominator
    return {s.x0, a1 * s.x0 + s.v0, a1, s.omega_n * s.omega_n};
}

Sdof sdof_from_transfer_function(const SdofTransferFunction& tf) {
    if (!(tf.a0 > 0.0)) throw InputError(fmt::format("SDOF transfer function: a0 = omega_n^2 = {} must be > 0", tf.a0));
    const double omega_n = std::sqrt(tf.a0);
    const double zeta = tf.a1 / (2.0 * omega_n);
    // Numerator b1 s + b0 = x(0) s + (2 zeta omega_n x(0) + x'(0)).
    return {zeta, omega_n, tf.b1, tf.b0 - tf.a1 * tf.b1};
}

double magnification_factor(double r, double zeta) {
    if (!(r >= 0.0) || !(zeta >= 0.0))
        throw InputError(fmt::format("magnification factor: r = {} and zeta = {} must be >= 0", r, zeta));
    const double a = 1.0 - r * r, b = 2.0 * zeta * r;
    return 1.0 / std::sqrt(a * a + b * b);  // Eq D-18
}

HalfPowerRatios half_power_ratios(double zeta) {
    if (!(zeta > 0.0)) throw InputError(fmt::format("half-power ratios: zeta = {} must be > 0", zeta));
    // Eq D-14: r^2 = (1 - 2 zeta^2) -+ 2 zeta sqrt(1 + zeta^2).
    const double c = 1.0 - 2.0 * zeta * zeta, d = 2.0 * zeta * std::sqrt(1.0 + zeta * zeta);
    const double r1sq = c - d;
    return {r1sq >= 0.0 ? std::sqrt(r1sq) : std::numeric_limits<double>::quiet_NaN(), std::sqrt(c + d)};
}

HalfPowerRatios peak_half_power_ratios(double zeta) {
    if (!(zeta > 0.0) || !(zeta < 1.0 / std::sqrt(2.0)))
        throw InputError(fmt::format("peak half-power ratios: zeta = {} must be in (0, 1/sqrt 2): no resonance peak", zeta));
    const double c = 1.0 - 2.0 * zeta * zeta, d = 2.0 * zeta * std::sqrt(1.0 - zeta * zeta);
    const double r1sq = c - d;
    return {r1sq >= 0.0 ? std::sqrt(r1sq) : std::numeric_limits<double>::quiet_NaN(), std::sqrt(c + d)};
}

double half_power_estimate(double zeta) {
    const auto r = peak_half_power_ratios(zeta);
    return (r.r2 - r.r1) / (2.0 * std::sqrt(1.0 - 2.0 * zeta * zeta));
}

double max_zeta_with_resonance_peak() { return 1.0 / std::sqrt(2.0); }

}  // namespace fem::damping
