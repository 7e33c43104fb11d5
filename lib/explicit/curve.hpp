#pragma once
// Piecewise-linear load curve (LS-DYNA *DEFINE_CURVE): value(t) interpolates the points linearly
// and holds the end values outside them.
#include <string>
#include <utility>
#include <vector>

namespace fem {

class Curve {
public:
    Curve() = default;  // the constant 1
    /// Points (t_i, y_i) with strictly increasing t; throws InputError naming `name` otherwise.
    Curve(std::vector<std::pair<double, double>> points, std::string name = "curve");
    static Curve constant(double value);
    /// 1 for t < t_end (and t >= t_start), 0 afterwards: a load held then released (with a
    /// `ramp` long linear rise and fall to avoid a step; ramp = 0 makes the jumps sharp).
    static Curve pulse(double t_start, double t_end, double ramp = 0.0);
    double operator()(double t) const;
    const std::string& name() const { return name_; }

private:
    std::vector<std::pair<double, double>> p_;
    std::string name_ = "constant";
};

}  // namespace fem
