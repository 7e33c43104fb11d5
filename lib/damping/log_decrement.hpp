#pragma once
// Log decrement method, thesis Appendix D.1 (time domain): for a viscously damped free vibration the
// amplitude falls by the same factor e^delta every damped period, so
//   delta = (1/n) ln(x_0 / x_n)        (Eq D-2, with the cycles counted from 0)
//   zeta  = delta / sqrt(4 pi^2 + delta^2)   (Eq D-3).
// Valid for a response dominated by one mode; the fewer cycles the signal shows (zeta > 0.6 leaves
// almost no second cycle, Fig D-2), the less it can measure.
#include <cstddef>
#include <vector>

#include "damping/signal.hpp"

namespace fem::damping {

/// Eq D-3.
double zeta_from_log_decrement(double delta);
/// Eq D-2 inverted: delta = 2 pi zeta / sqrt(1 - zeta^2), for 0 <= zeta < 1.
double log_decrement_from_zeta(double zeta);
/// Eq D-2: (1/n) ln(x0 / xn) for two amplitudes n >= 1 cycles apart (both > 0).
double log_decrement(double x0, double xn, int n);

/// How amplitudes are read off the signal.
enum class Amplitude {
    /// Peak minus the following trough: immune to a constant offset (the signal need not oscillate
    /// about zero). For a damped sinusoid the extrema are exactly half a damped period apart, so
    /// peak-to-trough amplitudes fall by e^delta per cycle like the peaks themselves.
    PeakToTrough,
    /// The maxima themselves: the signal must oscillate about zero.
    Peaks,
};

struct LogDecrementOptions {
    double t_start = -1e300;       // ignore the signal before this time (e.g. while a load acts)
    std::size_t cycles = 0;        // n in Eq D-2; 0 = as many as the signal shows
    double min_swing_fraction = 1e-3;  // extrema hysteresis, as a fraction of the largest swing
    Amplitude amplitude = Amplitude::PeakToTrough;
};

struct LogDecrementResult {
    double delta = 0.0;       // Eq D-2 from the first and the n-th cycle
    double zeta = 0.0;        // Eq D-3
    int cycles = 0;           // n
    double delta_fit = 0.0;   // least-squares slope of ln(amplitude) over every cycle (GSL fit)
    double delta_fit_stderr = 0.0;
    double zeta_fit = 0.0;
    double damped_period = 0.0;  // mean spacing of the maxima
    double omega_d = 0.0;        // 2 pi / damped_period
    double omega_n = 0.0;        // omega_d / sqrt(1 - zeta^2)
    std::vector<Extremum> maxima;      // the maxima used, one per cycle
    std::vector<double> amplitudes;    // their amplitudes (see Amplitude)
};

/// Eq D-2/D-3 on a sampled response. Throws SolverError when the signal shows fewer than two
/// cycles (nothing to measure: heavily damped, too short, or not oscillating).
LogDecrementResult log_decrement(const SampledSignal& s, const LogDecrementOptions& options = {});

}  // namespace fem::damping
