#include "damping/log_decrement.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include <gsl/gsl_fit.h>

#include "core/error.hpp"

namespace fem::damping {

namespace {
constexpr double two_pi = 2.0 * std::numbers::pi;
}

double zeta_from_log_decrement(double delta) {
    if (!(delta >= 0.0) || !std::isfinite(delta))
        throw InputError(fmt::format("log decrement: delta = {} must be finite and >= 0", delta));
    return delta / std::sqrt(two_pi * two_pi + delta * delta);  // Eq D-3
}

double log_decrement_from_zeta(double zeta) {
    if (!(zeta >= 0.0) || !(zeta < 1.0))
        throw InputError(fmt::format("log decrement: zeta = {} must be in [0, 1) (no oscillation otherwise)", zeta));
    return two_pi * zeta / std::sqrt(1.0 - zeta * zeta);  // Eq D-2
}

double log_decrement(double x0, double xn, int n) {
    if (!(x0 > 0.0) || !(xn > 0.0) || n < 1)
        throw InputError(fmt::format("log decrement: amplitudes x0 = {}, xn = {} must be > 0 and n = {} >= 1", x0, xn, n));
    return std::log(x0 / xn) / n;  // Eq D-2
}

LogDecrementResult log_decrement(const SampledSignal& s, const LogDecrementOptions& options) {
    s.validate("log decrement signal", 5);
    if (!(options.min_swing_fraction >= 0.0) || !(options.min_swing_fraction < 1.0))
        throw InputError(fmt::format("log decrement: min_swing_fraction = {} must be in [0, 1)", options.min_swing_fraction));

    // The largest swing after t_start sets the hysteresis of the extremum search.
    double lo = 1e300, hi = -1e300;
    for (std::size_t i = 0; i < s.size(); ++i)
        if (s.time(i) >= options.t_start) lo = std::min(lo, s.x[i]), hi = std::max(hi, s.x[i]);
    const auto extrema = find_extrema(s, options.min_swing_fraction * (hi - lo), options.t_start);

    LogDecrementResult r;
    for (std::size_t k = 0; k < extrema.size(); ++k) {
        if (!extrema[k].is_maximum) continue;
        double a = 0.0;
        if (options.amplitude == Amplitude::PeakToTrough) {
            if (k + 1 >= extrema.size()) break;  // no trough after the last peak
            a = extrema[k].x - extrema[k + 1].x;
        } else {
            a = extrema[k].x;
            if (!(a > 0.0)) continue;  // a peak below zero: the signal is not centred on zero
        }
        r.maxima.push_back(extrema[k]);
        r.amplitudes.push_back(a);
    }
    const int available = static_cast<int>(r.amplitudes.size()) - 1;  // whole cycles between peaks
    if (available < 1)
        throw SolverError(fmt::format("log decrement: the signal shows {} peak(s) after t = {:g} s, at least two cycles' "
                                      "worth are needed (heavily damped, too short, or not oscillating)",
                                      r.amplitudes.size(), std::max(options.t_start, s.t0)));
    const int n = options.cycles == 0 ? available : static_cast<int>(options.cycles);
    if (n > available)
        throw SolverError(fmt::format("log decrement: {} cycles requested, the signal shows {}", n, available));
    r.maxima.resize(n + 1);
    r.amplitudes.resize(n + 1);
    r.cycles = n;
    r.delta = log_decrement(r.amplitudes.front(), r.amplitudes.back(), n);  // Eq D-2
    r.zeta = zeta_from_log_decrement(r.delta);                              // Eq D-3

    // Least squares over every cycle: ln a_k = c - delta k (uses all peaks, not just the two ends).
    if (n >= 2) {
        std::vector<double> k(n + 1), ln_a(n + 1);
        for (int i = 0; i <= n; ++i) k[i] = i, ln_a[i] = std::log(r.amplitudes[i]);
        double c0, c1, cov00, cov01, cov11, sumsq;
        gsl_fit_linear(k.data(), 1, ln_a.data(), 1, n + 1, &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
        r.delta_fit = -c1;
        // cov11 from gsl_fit_linear is scaled by the residual variance: the fit's own standard error.
        r.delta_fit_stderr = std::sqrt(cov11);
    } else {
        r.delta_fit = r.delta;
    }
    r.zeta_fit = zeta_from_log_decrement(std::max(0.0, r.delta_fit));

    r.damped_period = (r.maxima.back().t - r.maxima.front().t) / n;
    r.omega_d = two_pi / r.damped_period;
    r.omega_n = r.omega_d / std::sqrt(1.0 - r.zeta * r.zeta);
    return r;
}

}  // namespace fem::damping
