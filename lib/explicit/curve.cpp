#include "explicit/curve.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fem {

Curve::Curve(std::vector<std::pair<double, double>> points, std::string name)
    : p_(std::move(points)), name_(std::move(name)) {
    if (p_.empty()) throw InputError(fmt::format("load curve '{}' has no points", name_));
    for (std::size_t i = 0; i < p_.size(); ++i) {
        if (!std::isfinite(p_[i].first) || !std::isfinite(p_[i].second))
            throw InputError(fmt::format("load curve '{}': point {} is not finite", name_, i));
        if (i > 0 && !(p_[i].first > p_[i - 1].first))
            throw InputError(fmt::format("load curve '{}': times must increase (point {} at t = {} after t = {})",
                                         name_, i, p_[i].first, p_[i - 1].first));
    }
}

Curve Curve::constant(double value) { return Curve({{0.0, value}}, fmt::format("constant {}", value)); }

Curve Curve::pulse(double t0, double t1, double ramp) {
    if (!(t1 > t0) || ramp < 0 || 2 * ramp > t1 - t0)
        throw InputError(fmt::format("pulse curve: need t_end > t_start and 2 ramp <= duration (got {}, {}, {})", t0,
                                     t1, ramp));
    if (ramp == 0.0) {
        const double eps = 1e-12 * std::max(1.0, std::abs(t1));
        return Curve({{t0 - eps, 0.0}, {t0, 1.0}, {t1, 1.0}, {t1 + eps, 0.0}}, "pulse");
    }
    return Curve({{t0, 0.0}, {t0 + ramp, 1.0}, {t1 - ramp, 1.0}, {t1, 0.0}}, "pulse");
}

double Curve::operator()(double t) const {
    if (p_.empty()) return 1.0;
    if (t <= p_.front().first) return p_.front().second;
    if (t >= p_.back().first) return p_.back().second;
    const auto it = std::upper_bound(p_.begin(), p_.end(), t, [](double v, const auto& q) { return v < q.first; });
    const auto& b = *it;
    const auto& a = *(it - 1);
    return a.second + (b.second - a.second) * (t - a.first) / (b.first - a.first);
}

}  // namespace fem
