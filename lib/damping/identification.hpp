#pragma once
// The computational/experimental damping identification of thesis Sec 2.5.2 (Fig 2-15), written as
// generic algorithms over a response function alpha -> sampled response (the study plugs in the
// explicit FE solver with mass-proportional damping C = alpha M; the unit tests plug in an SDOF).
//
//   Step 1  critical alpha: bracket and bisect alpha between an oscillating and a non-oscillating
//           response                                              -> find_critical_alpha
//   Step 2  shortcut: measure zeta by log decrement at a guess alpha_g; for mass-proportional damping
//           of one mode zeta = alpha / (2 omega), so alpha_cr = alpha_g / zeta   -> estimate_critical_alpha
//   Step 3  underdamped structure: alpha = zeta_experiment x alpha_cr (a product; no function)
//   Step 4  overdamped structure: trial alphas until the response matches a measured curve
//                                                                  -> match_alpha
#include <functional>
#include <optional>
#include <vector>

#include "damping/log_decrement.hpp"
#include "damping/signal.hpp"

namespace fem::damping {

/// Response of the damped model for a mass-proportional coefficient alpha (1/s).
using ResponseFunction = std::function<SampledSignal(double alpha)>;

/// When is a response oscillatory? A non-oscillatory (critically or overdamped) free response of one
/// mode is a sum of two decaying exponentials, which crosses its final value at most once; an
/// underdamped one crosses it again every half period. So: oscillating <=> at least `min_crossings`
/// (2) crossings of the final value after t_start. The hysteresis band is what the detector can
/// resolve: near alpha_cr the second overshoot is tiny (its size relative to the initial deviation is
/// e^-delta, delta the log decrement of Eq D-2), so a band b finds the alpha whose delta = ln(x0 / b).
struct OscillationOptions {
    double t_start = -1e300;                  // count after this time (e.g. the end of the load)
    std::optional<double> final_value;        // the level crossed; default: the last sample
    double band = 0.0;                        // absolute hysteresis half-width
    double relative_band = 0.0;               // ... or this fraction of the largest deviation after t_start
    int min_crossings = 2;
};

struct OscillationCheck {
    int crossings = 0;
    bool oscillating = false;
    double final_value = 0.0;
    double band = 0.0;  // the band used
};
OscillationCheck detect_oscillation(const SampledSignal& s, const OscillationOptions& options = {});

struct CriticalAlphaOptions {
    double alpha_lo = 1.0;    // first guess of an alpha whose response oscillates (> 0)
    double alpha_hi = 100.0;  // first guess of an alpha whose response does not (> alpha_lo)
    double rel_tolerance = 1e-3;  // stop when alpha_hi / alpha_lo - 1 < rel_tolerance
    int max_evaluations = 40;     // of the response function (each may be an FE run)
    double expand = 4.0;          // factor by which a wrong first guess is moved outward
    OscillationOptions oscillation;
};

struct AlphaTrial {
    double alpha = 0.0;
    int crossings = 0;
    bool oscillating = false;
};

struct CriticalAlphaResult {
    double alpha_cr = 0.0;               // geometric mean of the final bracket
    double alpha_oscillating = 0.0;      // largest alpha seen oscillating
    double alpha_non_oscillating = 0.0;  // smallest alpha seen not oscillating
    int evaluations = 0;
    bool converged = false;              // false: max_evaluations ran out first (bracket still valid)
    std::vector<AlphaTrial> trials;      // in the order evaluated
};

/// Sec 2.5.2 step 1: bisection (GSL bisection solver on ln alpha, fed the sign +-1 of "does not
/// oscillate") between an oscillating and a non-oscillating alpha. The first guesses are moved
/// outward by `expand` until they bracket. Throws SolverError when no bracket is found within the
/// budget, InputError for bad options.
CriticalAlphaResult find_critical_alpha(const ResponseFunction& response, const CriticalAlphaOptions& options);

/// Sec 2.5.2 step 2: alpha_cr ~ alpha_g / zeta, zeta measured by log decrement (Eq D-3) on the
/// response at alpha_g. Exact for mass-proportional damping of a single mode.
double critical_alpha_from_log_decrement(double alpha_guess, double zeta);
struct LogDecrementEstimate {
    double alpha_guess = 0.0;
    double alpha_cr = 0.0;
    LogDecrementResult measurement;
};
LogDecrementEstimate estimate_critical_alpha(const ResponseFunction& response, double alpha_guess,
                                             const LogDecrementOptions& options = {});

/// Root-mean-square difference between `response` (linearly interpolated, GSL) and `target` at the
/// target's sample times from t_start on that both cover. Throws SolverError when they share no time.
double rms_misfit(const SampledSignal& response, const SampledSignal& target, double t_start = -1e300);

struct MatchOptions {
    double alpha_min = 0.1, alpha_max = 1000.0;  // search range (> 0)
    int grid = 13;               // log-spaced trials that locate the best bracket before Brent
    double rel_tolerance = 1e-6; // on alpha
    int max_iterations = 100;
    double t_start = -1e300;     // compare from this time on
};
struct MatchResult {
    double alpha = 0.0;
    double misfit = 0.0;
    int evaluations = 0;
    bool converged = false;
    std::vector<std::pair<double, double>> trials;  // (alpha, misfit) in the order evaluated
};

/// Sec 2.5.2 step 4: the alpha whose response best matches `target` (least RMS misfit): a log-spaced
/// grid of trial alphas, then GSL's Brent minimizer on ln alpha around the best one. Throws
/// SolverError when the best trial lies on the bound of the range (widen it).
MatchResult match_alpha(const ResponseFunction& response, const SampledSignal& target, const MatchOptions& options);

}  // namespace fem::damping
