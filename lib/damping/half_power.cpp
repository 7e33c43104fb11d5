#include "damping/half_power.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <memory>
#include <numbers>

#include <gsl/gsl_fft_real.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_spline.h>

#include "core/error.hpp"
#include "damping/gsl_guard.hpp"

namespace fem::damping {

double zeta_from_half_power(double omega_1, double omega_2, double omega_n) {
    if (!(omega_n > 0.0) || !(omega_2 > omega_1) || !(omega_1 >= 0.0))
        throw InputError(fmt::format("half-power: need 0 <= omega_1 < omega_2 and omega_n > 0 (got {}, {}, {})",
                                     omega_1, omega_2, omega_n));
    const double quality = omega_n / (omega_2 - omega_1);  // Eq D-17
    return 1.0 / (2.0 * quality);
}

namespace {

using Function = std::function<double(double)>;

// Brent minimum of f on [a, b] given an interior m with f(m) < f(a), f(b).
double brent_minimum(const Function& f, double a, double m, double b) {
    detail::GslErrorsOff guard;
    std::unique_ptr<gsl_min_fminimizer, decltype(&gsl_min_fminimizer_free)> s(
        gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent), gsl_min_fminimizer_free);
    detail::GslCallback F(f);
    const int status = gsl_min_fminimizer_set(s.get(), F.get(), m, a, b);
    F.rethrow_if_failed();
    if (status != GSL_SUCCESS) throw SolverError(fmt::format("half-power: peak not bracketed in [{}, {}]", a, b));
    for (int it = 0; it < 200; ++it) {
        gsl_min_fminimizer_iterate(s.get());
        F.rethrow_if_failed();
        const double lo = gsl_min_fminimizer_x_lower(s.get()), hi = gsl_min_fminimizer_x_upper(s.get());
        if (gsl_min_test_interval(lo, hi, 0.0, 1e-12) == GSL_SUCCESS) break;
    }
    return gsl_min_fminimizer_x_minimum(s.get());
}

// Brent root of f on [a, b] (f(a), f(b) of opposite sign).
double brent_root(const Function& f, double a, double b) {
    detail::GslErrorsOff guard;
    std::unique_ptr<gsl_root_fsolver, decltype(&gsl_root_fsolver_free)> s(
        gsl_root_fsolver_alloc(gsl_root_fsolver_brent), gsl_root_fsolver_free);
    detail::GslCallback F(f);
    const int status = gsl_root_fsolver_set(s.get(), F.get(), a, b);
    F.rethrow_if_failed();
    if (status != GSL_SUCCESS) throw SolverError(fmt::format("half-power: crossing not bracketed in [{}, {}]", a, b));
    for (int it = 0; it < 200; ++it) {
        gsl_root_fsolver_iterate(s.get());
        F.rethrow_if_failed();
        const double lo = gsl_root_fsolver_x_lower(s.get()), hi = gsl_root_fsolver_x_upper(s.get());
        if (gsl_root_test_interval(lo, hi, 0.0, 1e-13) == GSL_SUCCESS) break;
    }
    return gsl_root_fsolver_root(s.get());
}

// The common algorithm on values g[i] = |H(w[i])| of a grid with a refining function `f` between
// grid points: peak at the largest interior value, then the first grid interval on either side
// where f drops below peak / sqrt 2.
HalfPowerResult half_power_on_grid(const std::vector<double>& w, const std::vector<double>& g, const Function& f) {
    const std::size_t n = w.size();
    const std::size_t i = static_cast<std::size_t>(std::max_element(g.begin(), g.end()) - g.begin());
    if (i == 0 || i + 1 >= n)
        throw SolverError(fmt::format("half-power: the FRF magnitude is largest at the end of the range "
                                      "(omega = {:g} rad/s): no resonance peak inside it", w[i]));
    HalfPowerResult r;
    const Function minus_f = [&](double x) { return -f(x); };
    r.omega_peak = brent_minimum(minus_f, w[i - 1], w[i], w[i + 1]);
    r.peak = f(r.omega_peak);
    const double level = r.peak / std::sqrt(2.0);
    const Function above = [&](double x) { return f(x) - level; };
    std::size_t j = i;
    while (j > 0 && g[j] >= level) --j;
    if (g[j] >= level)
        throw SolverError(fmt::format("half-power: below the peak at {:g} rad/s the FRF never falls to peak / sqrt 2 "
                                      "(lowest value {:.3g} x peak): damping too heavy or range too narrow",
                                      r.omega_peak, g[0] / r.peak));
    r.omega_1 = brent_root(above, w[j], j + 1 == i ? r.omega_peak : w[j + 1]);
    std::size_t k = i;
    while (k + 1 < n && g[k] >= level) ++k;
    if (g[k] >= level)
        throw SolverError(fmt::format("half-power: above the peak at {:g} rad/s the FRF never falls to peak / sqrt 2 "
                                      "inside the range", r.omega_peak));
    r.omega_2 = brent_root(above, k - 1 == i ? r.omega_peak : w[k - 1], w[k]);
    r.quality = r.omega_peak / (r.omega_2 - r.omega_1);
    r.zeta = zeta_from_half_power(r.omega_1, r.omega_2, r.omega_peak);  // Eq D-17
    return r;
}

}  // namespace

HalfPowerResult half_power_bandwidth(std::span<const double> omega, std::span<const double> magnitude) {
    if (omega.size() != magnitude.size() || omega.size() < 5)
        throw InputError(fmt::format("half-power: {} frequencies and {} magnitudes; equal numbers >= 5 needed",
                                     omega.size(), magnitude.size()));
    for (std::size_t i = 1; i < omega.size(); ++i)
        if (!(omega[i] > omega[i - 1]))
            throw InputError(fmt::format("half-power: frequencies must increase (sample {}: {} after {})", i, omega[i], omega[i - 1]));
    std::vector<double> w(omega.begin(), omega.end()), g(magnitude.begin(), magnitude.end());
    // A cubic spline through the samples refines the peak and the crossings between samples.
    std::unique_ptr<gsl_interp_accel, decltype(&gsl_interp_accel_free)> acc(gsl_interp_accel_alloc(), gsl_interp_accel_free);
    std::unique_ptr<gsl_spline, decltype(&gsl_spline_free)> spline(gsl_spline_alloc(gsl_interp_cspline, w.size()), gsl_spline_free);
    gsl_spline_init(spline.get(), w.data(), g.data(), w.size());
    const Function f = [&](double x) { return gsl_spline_eval(spline.get(), x, acc.get()); };
    return half_power_on_grid(w, g, f);
}

HalfPowerResult half_power_bandwidth(const std::function<double(double)>& magnitude, double omega_lo, double omega_hi,
                                     int grid) {
    if (!(omega_lo >= 0.0) || !(omega_hi > omega_lo) || grid < 5)
        throw InputError(fmt::format("half-power: need 0 <= omega_lo < omega_hi and grid >= 5 (got {}, {}, {})",
                                     omega_lo, omega_hi, grid));
    std::vector<double> w(grid), g(grid);
    for (int i = 0; i < grid; ++i) {
        w[i] = omega_lo + (omega_hi - omega_lo) * i / (grid - 1);
        g[i] = magnitude(w[i]);
    }
    return half_power_on_grid(w, g, magnitude);
}

Spectrum amplitude_spectrum(const SampledSignal& s, const SpectrumOptions& options) {
    s.validate("amplitude spectrum signal", 16);
    if (options.pad_factor < 1) throw InputError(fmt::format("amplitude spectrum: pad_factor = {} must be >= 1", options.pad_factor));
    const std::size_t n = s.size();
    const std::size_t tail = std::max<std::size_t>(2, n / 20);
    double final_value = 0.0, tail_lo = 1e300, tail_hi = -1e300, lo = 1e300, hi = -1e300;
    for (std::size_t i = n - tail; i < n; ++i)
        final_value += s.x[i] / tail, tail_lo = std::min(tail_lo, s.x[i]), tail_hi = std::max(tail_hi, s.x[i]);
    for (double v : s.x) lo = std::min(lo, v), hi = std::max(hi, v);
    if (tail_hi - tail_lo > options.max_tail_fraction * (hi - lo))
        throw SolverError(fmt::format("amplitude spectrum: the response has not died out in the record (its last 5 % "
                                      "still swings by {:.3g} of the largest swing, limit {:g}); a rectangular window "
                                      "would leak: record longer", (tail_hi - tail_lo) / (hi - lo), options.max_tail_fraction));
    std::size_t m = 1;
    while (m < n * static_cast<std::size_t>(options.pad_factor)) m *= 2;
    std::vector<double> data(m, 0.0);
    const double offset = options.remove_final_value ? final_value : 0.0;
    for (std::size_t i = 0; i < n; ++i) data[i] = s.x[i] - offset;
    {
        detail::GslErrorsOff guard;
        if (gsl_fft_real_radix2_transform(data.data(), 1, m) != GSL_SUCCESS)
            throw SolverError(fmt::format("amplitude spectrum: GSL FFT of {} points failed", m));
    }
    // Half-complex layout: data[k] = Re X_k (k <= m/2), data[m-k] = Im X_k (0 < k < m/2).
    Spectrum out;
    const double dw = 2.0 * std::numbers::pi / (m * s.dt);
    for (std::size_t k = 0; k <= m / 2; ++k) {
        const double re = data[k], im = (k == 0 || k == m / 2) ? 0.0 : data[m - k];
        out.omega.push_back(k * dw);
        out.magnitude.push_back(std::hypot(re, im) * s.dt);  // dt: the sum approximates the integral
    }
    return out;
}

HalfPowerResult half_power_from_signal(const SampledSignal& s, const SpectrumOptions& options, double omega_lo,
                                       double omega_hi) {
    const Spectrum sp = amplitude_spectrum(s, options);
    std::vector<double> w, g;
    for (std::size_t k = 1; k < sp.omega.size(); ++k)  // skip DC
        if (sp.omega[k] >= omega_lo && sp.omega[k] <= omega_hi) w.push_back(sp.omega[k]), g.push_back(sp.magnitude[k]);
    return half_power_bandwidth(w, g);
}

}  // namespace fem::damping
