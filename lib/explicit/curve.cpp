#include "explicit/curve.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fem {

Curve::Curve(std::vector<std::pair<double, double>> points, std::string name)
    : p_(std::move(points)), name_(std::move(name)) {
    if (p_.empty()) throw InputError(fmt::format("curve '{}' has no points", name_));
    for (std::size_t i = 0; i < p_.size(); ++i) {
        if (!std::isfinite(p_[i].first) || !std::isfinite(p_[i].second))
            throw InputError(fmt::format("curve '{}': point {} is not finite", name_, i));
        if (i > 0 && p_[i].first < p_[i - 1].first)
            throw InputError(fmt::format("curve '{}': times must not decrease (point {} at t = {} after t = {})", name_,
                                         i, p_[i].first, p_[i - 1].first));
        if (i > 1 && p_[i].first == p_[i - 2].first)
            throw InputError(fmt::format("curve '{}': three points at t = {} (a step is two points with the same "
                                         "time: the value before and the value from then on)",
                                         name_, p_[i].first));
    }
}

Curve Curve::constant(double value) { return Curve({{0.0, value}}, fmt::format("constant {}", value)); }

Curve Curve::pulse(double t0, double t1, double ramp) {
    if (!(t1 > t0) || ramp < 0 || 2 * ramp > t1 - t0)
        throw InputError(fmt::format("pulse curve: need t_end > t_start and 2 ramp <= duration (got {}, {}, {})", t0,
                                     t1, ramp));
    if (ramp == 0.0) return Curve({{t0, 0.0}, {t0, 1.0}, {t1, 1.0}, {t1, 0.0}}, "pulse");
    return Curve({{t0, 0.0}, {t0 + ramp, 1.0}, {t1 - ramp, 1.0}, {t1, 0.0}}, "pulse");
}

Curve Curve::step(double t_on) { return Curve({{t_on, 0.0}, {t_on, 1.0}}, fmt::format("step at {}", t_on)); }

Curve Curve::steps(const std::vector<std::pair<double, double>>& sv, std::string name) {
    if (sv.empty()) throw InputError(fmt::format("curve '{}': no steps", name));
    std::vector<std::pair<double, double>> p{sv[0]};
    for (std::size_t i = 1; i < sv.size(); ++i) {
        if (!(sv[i].first > sv[i - 1].first))
            throw InputError(fmt::format("curve '{}': step times must increase (step {} at t = {} after t = {})", name,
                                         i, sv[i].first, sv[i - 1].first));
        p.push_back({sv[i].first, sv[i - 1].second});  // the value held up to the step
        p.push_back(sv[i]);                            // and the new one from it
    }
    return Curve(std::move(p), std::move(name));
}

double Curve::operator()(double t) const {
    if (p_.empty()) return 1.0;
    if (t < p_.front().first) return p_.front().second;
    if (t >= p_.back().first) return p_.back().second;
    // b: the first point after t; a: the one before it, which is the later point of a step at t.
    const auto it = std::upper_bound(p_.begin(), p_.end(), t, [](double v, const auto& q) { return v < q.first; });
    const auto& b = *it;
    const auto& a = *(it - 1);
    return a.second + (b.second - a.second) * (t - a.first) / (b.first - a.first);
}

double Curve::area(double a, double b) const {
    if (p_.empty()) return b - a;
    double s = 0.0;
    const auto& [t0, y0] = p_.front();
    const auto& [tn, yn] = p_.back();
    if (a < t0) s += y0 * (std::min(b, t0) - a);
    for (std::size_t k = 0; k + 1 < p_.size(); ++k) {
        const auto& [ta, ya] = p_[k];
        const auto& [tb, yb] = p_[k + 1];
        const double lo = std::max(a, ta), hi = std::min(b, tb);
        if (!(tb > ta) || !(hi > lo)) continue;  // a step, or no overlap
        // (written out, not as a lambda: clang 14, which `make fuzz` uses, cannot capture structured bindings)
        const double y_lo = ya + (yb - ya) * (lo - ta) / (tb - ta);
        const double y_hi = ya + (yb - ya) * (hi - ta) / (tb - ta);
        s += 0.5 * (y_lo + y_hi) * (hi - lo);
    }
    if (b > tn) s += yn * (b - std::max(a, tn));
    return s;
}

Curve Curve::shifted(double t0) const {
    if (p_.empty() || t0 == 0.0) return *this;
    std::vector<std::pair<double, double>> q;
    std::size_t k = 0;
    while (k < p_.size() && p_[k].first < t0) ++k;
    // The value in force at t0, unless a point (or the later point of a step) lies at t0.
    if (k == p_.size() || p_[k].first > t0) q.push_back({0.0, (*this)(t0)});
    for (; k < p_.size(); ++k) q.push_back({p_[k].first - t0, p_[k].second});
    Curve c;
    c.p_ = std::move(q);
    c.name_ = name_;
    return c;
}

double Curve::integral(double t) const { return t >= 0.0 ? area(0.0, t) : -area(t, 0.0); }

}  // namespace fem
