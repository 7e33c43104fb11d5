#include "damping/signal.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <fmt/format.h>

#include "core/error.hpp"

namespace fem::damping {

void SampledSignal::validate(const char* what, std::size_t min_samples) const {
    if (!(dt > 0.0) || !std::isfinite(dt))
        throw InputError(fmt::format("{}: sampling interval dt = {} must be positive", what, dt));
    if (x.size() < min_samples)
        throw InputError(fmt::format("{}: {} samples, at least {} needed", what, x.size(), min_samples));
    for (std::size_t i = 0; i < x.size(); ++i)
        if (!std::isfinite(x[i])) throw InputError(fmt::format("{}: sample {} is {}", what, i, x[i]));
}

namespace {
// Vertex of the parabola through (-1, ym), (0, y0), (1, yp): offset in samples and value.
Extremum parabolic(const SampledSignal& s, std::size_t i, bool is_max) {
    const double ym = s.x[i - 1], y0 = s.x[i], yp = s.x[i + 1];
    const double curvature = ym - 2.0 * y0 + yp;
    double p = 0.0, y = y0;
    if (curvature != 0.0) {
        p = 0.5 * (ym - yp) / curvature;
        y = y0 - 0.25 * (ym - yp) * p;
    }
    return {s.time(i) + p * s.dt, y, is_max, i};
}
}  // namespace

std::vector<Extremum> find_extrema(const SampledSignal& s, double min_swing, double t_start) {
    s.validate("find_extrema");
    if (!(min_swing >= 0.0)) throw InputError(fmt::format("find_extrema: min_swing = {} must be >= 0", min_swing));
    std::vector<Extremum> kept;
    for (std::size_t i = 1; i + 1 < s.size(); ++i) {
        if (s.time(i) < t_start) continue;
        const double ym = s.x[i - 1], y0 = s.x[i], yp = s.x[i + 1];
        const bool is_max = y0 > ym && y0 >= yp;
        const bool is_min = y0 < ym && y0 <= yp;
        if (!is_max && !is_min) continue;
        const Extremum e = parabolic(s, i, is_max);
        if (kept.empty()) {
            kept.push_back(e);
        } else if (kept.back().is_maximum == e.is_maximum) {
            // Same kind again (the swing between was below min_swing): keep the more extreme one.
            if (e.is_maximum ? e.x > kept.back().x : e.x < kept.back().x) kept.back() = e;
        } else if (std::abs(e.x - kept.back().x) > min_swing) {
            kept.push_back(e);
        }
    }
    return kept;
}

int count_crossings(const SampledSignal& s, double level, double band, double t_start) {
    s.validate("count_crossings", 1);
    if (!(band >= 0.0)) throw InputError(fmt::format("count_crossings: band = {} must be >= 0", band));
    int crossings = 0;
    int side = 0;  // +1 above level + band, -1 below level - band, 0 not yet known
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s.time(i) < t_start) continue;
        const double d = s.x[i] - level;
        const int now = d > band ? 1 : (d < -band ? -1 : 0);
        if (now == 0) continue;
        if (side != 0 && now != side) ++crossings;
        side = now;
    }
    return crossings;
}

}  // namespace fem::damping

namespace fem::damping {

SampledSignal cfc_filter(const SampledSignal& s, double cfc) {
    s.validate("cfc_filter");
    if (!(cfc > 0.0) || !std::isfinite(cfc)) throw InputError(fmt::format("cfc_filter: CFC = {} must be positive", cfc));
    if (1.0 / s.dt < 10.0 * cfc)
        throw InputError(fmt::format("cfc_filter: sampling rate {:.4g} Hz is below 10 x CFC {} (SAE J211)", 1.0 / s.dt,
                                     cfc));
    // J211-1 Appendix C coefficients: the analogue design frequency 2.0775 x CFC, pre-warped for the
    // bilinear transform.
    const double wd = 2.0 * std::numbers::pi * cfc * 2.0775;
    const double wa = std::tan(0.5 * wd * s.dt);
    const double den = 1.0 + std::sqrt(2.0) * wa + wa * wa;
    const double a0 = wa * wa / den, a1 = 2.0 * a0, a2 = a0;
    const double b1 = -2.0 * (wa * wa - 1.0) / den;
    const double b2 = (-1.0 + std::sqrt(2.0) * wa - wa * wa) / den;
    auto pass = [&](std::vector<double>& x) {  // in place, y[i] from x[i..i-2] and y[i-1..i-2]
        double xm1 = x.front(), xm2 = x.front(), ym1 = x.front(), ym2 = x.front();
        for (double& xi : x) {
            const double y = a0 * xi + a1 * xm1 + a2 * xm2 + b1 * ym1 + b2 * ym2;
            xm2 = xm1, xm1 = xi, ym2 = ym1, ym1 = y;
            xi = y;
        }
    };
    SampledSignal out = s;
    pass(out.x);
    std::reverse(out.x.begin(), out.x.end());
    pass(out.x);
    std::reverse(out.x.begin(), out.x.end());
    return out;
}

}  // namespace fem::damping
