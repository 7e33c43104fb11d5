#pragma once
// The one time-curve type of the library (LS-DYNA *DEFINE_CURVE): the scale factor of loads and
// gravity, prescribed velocities and displacements, the angular speed of a rigid rotation and the
// speed of a rigid translation (explicit/rigid_motion.hpp).
//
// value(t) interpolates the points linearly and holds the end values outside them. A repeated
// abscissa is a step: the points (t1, a), (t1, b) jump from a to b at t1, and the value AT t1 is
// the later one, b (a load switched on at t1 acts at t1; a motion stopped at t1 is at rest at t1).
// integral(t) = int_0^t value(s) ds is exact: trapezoids between the points (linear there), the
// held end values outside, nothing from a step. Rigid motions take their angle and translation
// from it, so a drum turned at a piecewise speed is where the schedule puts it, to round-off.
//
//   Curve::pulse(0.0, 0.2)                              1 on [0, 0.2), 0 afterwards (a held tip load)
//   Curve({{0, 0}, {0.05, 2.095}})                      a ramp to 20 rpm in 50 ms, held
//   Curve::steps({{0.0, 2.0}, {1.2, 0.5}, {1.5, 0.0}})  2 rad/s, 0.5 rad/s from 1.2 s, stopped at 1.5 s
#include <string>
#include <utility>
#include <vector>

namespace fem {

class Curve {
public:
    Curve() = default;  // the constant 1
    /// Points (t_i, y_i) with non-decreasing t; one abscissa may appear twice (a step), not three
    /// times. Throws InputError naming `name` otherwise, or for a non-finite point.
    Curve(std::vector<std::pair<double, double>> points, std::string name = "curve");
    static Curve constant(double value);
    /// 1 for t_start <= t < t_end, 0 outside: a load held, then released. With ramp > 0 a linear
    /// rise over [t_start, t_start + ramp] and fall over [t_end - ramp, t_end] instead of the steps.
    static Curve pulse(double t_start, double t_end, double ramp = 0.0);
    /// 0 before t_on, 1 from t_on on (gravity switched on at t_on).
    static Curve step(double t_on);
    /// Piecewise constant: (t_i, v_i) means the value v_i from t_i until the next t_{i+1} (steps at
    /// every t_i, i > 0); v_0 also before t_0. Times strictly increasing.
    static Curve steps(const std::vector<std::pair<double, double>>& start_and_value, std::string name = "steps");

    double operator()(double t) const;
    /// int_0^t value(s) ds (negative for t < 0), exact for the piecewise-linear curve.
    double integral(double t) const;
    /// The curve seen from time t0 on: c'(tau) = c(tau + t0). Points before t0 are replaced by one
    /// point (0, c(t0)) (none when a point lies at t0), so a schedule that starts at 0 and is shifted
    /// by t0 is the schedule written from t0 on, point for point (hand::seen_from).
    Curve shifted(double t0) const;
    const std::string& name() const { return name_; }
    /// The points (empty for the default constant 1).
    const std::vector<std::pair<double, double>>& points() const { return p_; }

private:
    double area(double a, double b) const;  // int_a^b, a <= b
    std::vector<std::pair<double, double>> p_;
    std::string name_ = "constant";
};

}  // namespace fem
