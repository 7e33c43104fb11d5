#include "damping/identification.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <memory>

#include <gsl/gsl_interp.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_roots.h>

#include "core/error.hpp"
#include "damping/gsl_guard.hpp"

namespace fem::damping {

OscillationCheck detect_oscillation(const SampledSignal& s, const OscillationOptions& o) {
    s.validate("oscillation detection signal", 2);
    if (!(o.band >= 0.0) || !(o.relative_band >= 0.0) || o.min_crossings < 1)
        throw InputError(fmt::format("oscillation detection: band = {}, relative_band = {} must be >= 0 and "
                                     "min_crossings = {} >= 1", o.band, o.relative_band, o.min_crossings));
    OscillationCheck c;
    c.final_value = o.final_value.value_or(s.x.back());
    double largest = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i)
        if (s.time(i) >= o.t_start) largest = std::max(largest, std::abs(s.x[i] - c.final_value));
    c.band = std::max(o.band, o.relative_band * largest);
    c.crossings = count_crossings(s, c.final_value, c.band, o.t_start);
    c.oscillating = c.crossings >= o.min_crossings;
    return c;
}

CriticalAlphaResult find_critical_alpha(const ResponseFunction& response, const CriticalAlphaOptions& o) {
    if (!(o.alpha_lo > 0.0) || !(o.alpha_hi > o.alpha_lo))
        throw InputError(fmt::format("critical alpha search: need 0 < alpha_lo < alpha_hi (got {}, {})", o.alpha_lo, o.alpha_hi));
    if (!(o.rel_tolerance > 0.0) || o.max_evaluations < 2 || !(o.expand > 1.0))
        throw InputError(fmt::format("critical alpha search: rel_tolerance = {} > 0, max_evaluations = {} >= 2 and "
                                     "expand = {} > 1 needed", o.rel_tolerance, o.max_evaluations, o.expand));
    CriticalAlphaResult r;
    r.alpha_oscillating = 0.0;
    r.alpha_non_oscillating = 1e300;
    // The response function with a memory: the GSL bisection re-evaluates its bracket ends, and every
    // evaluation may be a whole FE run. Returns nullopt once the budget is spent.
    std::map<double, bool> memo;
    auto oscillating = [&](double alpha) -> std::optional<bool> {
        if (auto it = memo.find(alpha); it != memo.end()) return it->second;
        if (r.evaluations >= o.max_evaluations) return std::nullopt;
        ++r.evaluations;
        const auto check = detect_oscillation(response(alpha), o.oscillation);
        r.trials.push_back({alpha, check.crossings, check.oscillating});
        if (check.oscillating) r.alpha_oscillating = std::max(r.alpha_oscillating, alpha);
        else r.alpha_non_oscillating = std::min(r.alpha_non_oscillating, alpha);
        return memo[alpha] = check.oscillating;
    };
    // Bracket: move a wrong first guess outward (the other end then becomes a valid one).
    double lo = o.alpha_lo, hi = o.alpha_hi;
    auto no_bracket = [&] {
        return SolverError(fmt::format("critical alpha search: no bracket of oscillating / non-oscillating responses "
                                       "after {} evaluations (last tried {:g} and {:g})", r.evaluations, lo, hi));
    };
    for (auto osc = oscillating(lo); !osc || !*osc; osc = oscillating(lo)) {
        if (!osc) throw no_bracket();
        hi = lo, lo /= o.expand;
    }
    for (auto osc = oscillating(hi); !osc || *osc; osc = oscillating(hi)) {
        if (!osc) throw no_bracket();
        lo = hi, hi *= o.expand;
    }
    // Bisection in u = ln alpha, so that the relative tolerance on alpha is an absolute one on u and
    // a bracket spanning decades is halved geometrically. GSL's bisection uses only the sign of f:
    // -1 below alpha_cr (oscillates), +1 above.
    bool out_of_budget = false;
    const double ulo0 = std::log(lo), uhi0 = std::log(hi);
    detail::GslCallback F([&](double u) {
        // The bracket ends map back to the alphas already evaluated (exp(log(a)) may differ from a in
        // the last bit, which would cost a whole FE run twice).
        const double alpha = u == ulo0 ? lo : (u == uhi0 ? hi : std::exp(u));
        const auto osc = oscillating(alpha);
        if (!osc) out_of_budget = true;
        return osc.value_or(false) ? -1.0 : 1.0;
    });
    detail::GslErrorsOff guard;
    std::unique_ptr<gsl_root_fsolver, decltype(&gsl_root_fsolver_free)> s(
        gsl_root_fsolver_alloc(gsl_root_fsolver_bisection), gsl_root_fsolver_free);
    double ulo = ulo0, uhi = uhi0;
    const double tol_u = std::log1p(o.rel_tolerance);
    gsl_root_fsolver_set(s.get(), F.get(), ulo, uhi);  // both ends are memoized: no new evaluation
    F.rethrow_if_failed();
    while (!(r.converged = gsl_root_test_interval(ulo, uhi, tol_u, 0.0) == GSL_SUCCESS)) {
        gsl_root_fsolver_iterate(s.get());
        F.rethrow_if_failed();
        if (out_of_budget) break;
        ulo = gsl_root_fsolver_x_lower(s.get());
        uhi = gsl_root_fsolver_x_upper(s.get());
    }
    // The bracket of record is what was actually observed (bisection keeps every oscillating trial
    // below every non-oscillating one).
    r.alpha_cr = std::sqrt(r.alpha_oscillating * r.alpha_non_oscillating);
    return r;
}

double critical_alpha_from_log_decrement(double alpha_guess, double zeta) {
    if (!(alpha_guess > 0.0) || !(zeta > 0.0))
        throw InputError(fmt::format("critical alpha from log decrement: alpha_g = {} and zeta = {} must be > 0", alpha_guess, zeta));
    return alpha_guess / zeta;  // zeta = alpha / (2 omega) = alpha / alpha_cr
}

LogDecrementEstimate estimate_critical_alpha(const ResponseFunction& response, double alpha_guess,
                                             const LogDecrementOptions& options) {
    LogDecrementEstimate e;
    e.alpha_guess = alpha_guess;
    e.measurement = log_decrement(response(alpha_guess), options);
    e.alpha_cr = critical_alpha_from_log_decrement(alpha_guess, e.measurement.zeta);
    return e;
}

double rms_misfit(const SampledSignal& response, const SampledSignal& target, double t_start) {
    response.validate("misfit: response", 2);
    target.validate("misfit: target", 1);
    std::vector<double> t(response.size());
    for (std::size_t i = 0; i < t.size(); ++i) t[i] = response.time(i);
    std::unique_ptr<gsl_interp, decltype(&gsl_interp_free)> interp(gsl_interp_alloc(gsl_interp_linear, t.size()), gsl_interp_free);
    std::unique_ptr<gsl_interp_accel, decltype(&gsl_interp_accel_free)> acc(gsl_interp_accel_alloc(), gsl_interp_accel_free);
    gsl_interp_init(interp.get(), t.data(), response.x.data(), t.size());
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < target.size(); ++i) {
        const double ti = target.time(i);
        if (ti < t_start || ti < t.front() || ti > t.back()) continue;
        const double d = gsl_interp_eval(interp.get(), t.data(), response.x.data(), ti, acc.get()) - target.x[i];
        sum += d * d;
        ++count;
    }
    if (count == 0) throw SolverError("misfit: the response and the target share no sample time");
    return std::sqrt(sum / count);
}

MatchResult match_alpha(const ResponseFunction& response, const SampledSignal& target, const MatchOptions& o) {
    if (!(o.alpha_min > 0.0) || !(o.alpha_max > o.alpha_min) || o.grid < 3 || !(o.rel_tolerance > 0.0))
        throw InputError(fmt::format("trial matching: need 0 < alpha_min < alpha_max, grid >= 3, rel_tolerance > 0 "
                                     "(got {}, {}, {}, {})", o.alpha_min, o.alpha_max, o.grid, o.rel_tolerance));
    MatchResult r;
    // Brent minimizes the mean square (smooth, parabolic near a perfect match) rather than the RMS
    // (which has a V-shaped, non-differentiable minimum at zero misfit).
    auto misfit_of_u = [&](double u) {
        const double alpha = std::exp(u);
        const double f = rms_misfit(response(alpha), target, o.t_start);
        ++r.evaluations;
        r.trials.emplace_back(alpha, f);
        return f * f;
    };
    // A log-spaced grid of trial alphas: the misfit need not be unimodal over decades.
    std::vector<double> u(o.grid), f(o.grid);
    for (int i = 0; i < o.grid; ++i) {
        u[i] = std::log(o.alpha_min) + (std::log(o.alpha_max) - std::log(o.alpha_min)) * i / (o.grid - 1);
        f[i] = misfit_of_u(u[i]);
    }
    const int k = static_cast<int>(std::min_element(f.begin(), f.end()) - f.begin());
    if (k == 0 || k == o.grid - 1)
        throw SolverError(fmt::format("trial matching: the best trial alpha = {:g} lies on the bound of [{:g}, {:g}]; "
                                      "widen the range", std::exp(u[k]), o.alpha_min, o.alpha_max));
    detail::GslErrorsOff guard;
    std::unique_ptr<gsl_min_fminimizer, decltype(&gsl_min_fminimizer_free)> s(
        gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent), gsl_min_fminimizer_free);
    detail::GslCallback F(misfit_of_u);
    if (gsl_min_fminimizer_set_with_values(s.get(), F.get(), u[k], f[k], u[k - 1], f[k - 1], u[k + 1], f[k + 1]) != GSL_SUCCESS)
        throw SolverError(fmt::format("trial matching: misfit not bracketed around alpha = {:g}", std::exp(u[k])));
    const double tol_u = std::log1p(o.rel_tolerance);
    for (int it = 0; it < o.max_iterations; ++it) {
        const int status = gsl_min_fminimizer_iterate(s.get());
        F.rethrow_if_failed();
        if (status != GSL_SUCCESS) break;
        if (gsl_min_test_interval(gsl_min_fminimizer_x_lower(s.get()), gsl_min_fminimizer_x_upper(s.get()), tol_u, 0.0) ==
            GSL_SUCCESS) {
            r.converged = true;
            break;
        }
    }
    r.alpha = std::exp(gsl_min_fminimizer_x_minimum(s.get()));
    r.misfit = std::sqrt(gsl_min_fminimizer_f_minimum(s.get()));
    return r;
}

}  // namespace fem::damping
