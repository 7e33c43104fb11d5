#pragma once
// A uniformly sampled response (a tip displacement from an experiment or from the explicit solver)
// and the elementary operations the damping identification needs: extrema with sub-sample
// (parabolic) interpolation, and crossings of a level with a hysteresis band.
#include <cstddef>
#include <vector>

namespace fem::damping {

/// x[i] sampled at t = t0 + i dt.
struct SampledSignal {
    double t0 = 0.0;
    double dt = 0.0;
    std::vector<double> x;

    double time(std::size_t i) const { return t0 + static_cast<double>(i) * dt; }
    std::size_t size() const { return x.size(); }
    /// Throws InputError when dt <= 0, a value is not finite, or there are fewer than `min_samples`.
    void validate(const char* what, std::size_t min_samples = 3) const;
};

/// A local extremum located between samples by fitting a parabola through the largest (smallest)
/// sample and its two neighbours.
struct Extremum {
    double t = 0.0;
    double x = 0.0;
    bool is_maximum = true;
    std::size_t index = 0;  // the sample nearest to it
};

/// Alternating maxima and minima of s from time t_start on. An extremum is kept only when it differs
/// from the previous kept one (of the other kind) by more than min_swing: a hysteresis that ignores
/// ripples (noise, round-off) smaller than min_swing. Interior samples only.
std::vector<Extremum> find_extrema(const SampledSignal& s, double min_swing = 0.0, double t_start = -1e300);

/// Number of times s crosses `level` from t_start on, counting a crossing only when the signal goes
/// from above level + band to below level - band or back (band >= 0).
int count_crossings(const SampledSignal& s, double level, double band = 0.0, double t_start = -1e300);

}  // namespace fem::damping

namespace fem::damping {

/// SAE J211-1 / ISO 6487 channel-frequency-class (CFC) low-pass filter, as crash and impact codes'
/// post-processors apply it to forces and accelerations (LS-PrePost's "SAE" filter): a two-pole
/// Butterworth run forward and then backward over the record, so four poles and no phase shift.
/// CFC 60 is flat to 60 Hz and 3 dB down at about 100 Hz (1.667 x CFC). The record must be uniformly
/// sampled at 10 x CFC or faster (J211's sampling rule): InputError otherwise. Both passes start
/// from the record's end value at rest, so a constant record passes unchanged.
SampledSignal cfc_filter(const SampledSignal& s, double cfc);

}  // namespace fem::damping
