#pragma once
// Half-power bandwidth method, thesis Appendix D.2 (frequency domain): on the magnitude of a
// frequency response function the two frequencies where it is 1/sqrt(2) of the resonance peak are
// omega_1 < omega_2, and zeta = 1 / (2 Q) with Q = omega_n / (omega_2 - omega_1) (Eq D-17).
// Eq D-17 is the light-damping limit of Eq D-14: the estimate grows too large as zeta grows, and the
// lower half-power point disappears above zeta = 0.383 (see sdof.hpp, half_power_ratios).
#include <functional>
#include <span>
#include <vector>

#include "damping/signal.hpp"

namespace fem::damping {

/// Eq D-17: zeta = (omega_2 - omega_1) / (2 omega_n).
double zeta_from_half_power(double omega_1, double omega_2, double omega_n);

struct HalfPowerResult {
    double omega_peak = 0.0;  // resonance (taken as omega_n in Eq D-17)
    double peak = 0.0;        // |H| at the peak
    double omega_1 = 0.0, omega_2 = 0.0;  // half-power points
    double quality = 0.0;     // Q = omega_peak / (omega_2 - omega_1)
    double zeta = 0.0;        // 1 / (2 Q)
};

/// On a sampled FRF magnitude (omega strictly increasing). The largest sample and the half-power
/// crossings on either side are refined on a cubic spline through the samples (GSL interpolation,
/// Brent minimizer for the peak, Brent root finder for the crossings). Throws SolverError when the
/// magnitude does not fall to peak / sqrt(2) on both sides inside the samples.
HalfPowerResult half_power_bandwidth(std::span<const double> omega, std::span<const double> magnitude);

/// On an FRF given as a function |H(omega)| on [omega_lo, omega_hi]: a grid of `grid` points
/// locates the peak and brackets the crossings, GSL Brent refines them to ~1e-12 relative.
HalfPowerResult half_power_bandwidth(const std::function<double(double)>& magnitude, double omega_lo,
                                     double omega_hi, int grid = 4001);

/// One-sided amplitude spectrum of a sampled transient, |X(omega)| ~ |integral x(t) e^{-i omega t} dt|,
/// by GSL's radix-2 real FFT.
struct SpectrumOptions {
    // Window: rectangular, i.e. none. A free or impulse response that has died out inside the record
    // is a transient whose Fourier transform needs no window; a Hann or similar window would multiply
    // it by a time function and widen the peak, i.e. add apparent damping. The record must therefore
    // cover the decay: the spectrum is refused when the last 5 % of the record still swings by more
    // than max_tail_fraction of the largest swing.
    double max_tail_fraction = 0.01;
    // Zero padding to the next power of two >= pad_factor x the record length, to sample the
    // spectrum finely enough for the spline through it (it adds no information).
    int pad_factor = 8;
    // Subtract the settled value (mean of the last 5 % of the record) before transforming, so that
    // a constant offset does not leak into the low frequencies as a box function's spectrum would.
    bool remove_final_value = true;
};
struct Spectrum {
    std::vector<double> omega;      // rad/s, 0 .. pi / dt
    std::vector<double> magnitude;  // |X| dt
};
Spectrum amplitude_spectrum(const SampledSignal& s, const SpectrumOptions& options = {});

/// The half-power method on a time signal: its amplitude spectrum, then half_power_bandwidth between
/// omega_lo and omega_hi (0 and infinity: the whole spectrum except the DC sample).
/// The signal should be an impulse response (or a free response, whose transform has the extra
/// numerator (s + 2 zeta omega_n) x(0) of Table 2-7).
HalfPowerResult half_power_from_signal(const SampledSignal& s, const SpectrumOptions& options = {},
                                       double omega_lo = 0.0, double omega_hi = 1e300);

}  // namespace fem::damping
