// The time curve (explicit/curve.hpp): values between, outside and at steps, and the exact integral
// against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "explicit/curve.hpp"
#include "explicit_test_support.hpp"

using namespace fem;

// A ramp 0 -> 2 over [0, 1], a step up to 5 at t = 1, held to t = 3, a step down to 0 at t = 3:
// integral t^2 on [0, 1], 1 + 5 (t - 1) on [1, 3], 11 afterwards.
TEST(Curve, StepsTakeTheLaterValueAndTheIntegralIsExact) {
    const Curve c({{0, 0}, {1, 2}, {1, 5}, {3, 5}, {3, 0}}, "ramp and steps");
    EXPECT_EQ(c(-1.0), 0.0);
    EXPECT_EQ(c(0.5), 1.0);
    EXPECT_EQ(c(std::nextafter(1.0, 0.0)), 2.0 * std::nextafter(1.0, 0.0));
    EXPECT_EQ(c(1.0), 5.0);  // at the step: the later value
    EXPECT_EQ(c(2.0), 5.0);
    EXPECT_EQ(c(std::nextafter(3.0, 0.0)), 5.0);
    EXPECT_EQ(c(3.0), 0.0);
    EXPECT_EQ(c(10.0), 0.0);
    for (double t : {0.0, 0.25, 0.5, 0.999, 1.0, 1.5, 2.0, 2.999, 3.0, 4.0, 100.0}) {
        const double exact = t <= 1 ? t * t : t <= 3 ? 1 + 5 * (t - 1) : 11.0;
        EXPECT_NEAR(c.integral(t), exact, 1e-15 * std::max(1.0, exact)) << t;
    }
    EXPECT_EQ(c.integral(-2.0), 0.0);  // the held value 0 before the first point
    // Its derivative is the curve away from the steps.
    for (double t : {0.3, 0.7, 1.6, 2.5, 5.0}) {
        const double h = 1e-6;
        EXPECT_NEAR((c.integral(t + h) - c.integral(t - h)) / (2 * h), c(t), 1e-8) << t;
    }
}

// A curve that starts before t = 0: integral from 0, negative backwards. y = 2 + t on [-1, 1].
TEST(Curve, IntegralIsMeasuredFromTimeZero) {
    const Curve c({{-1, 1}, {1, 3}});
    EXPECT_NEAR(c.integral(0.5), 2 * 0.5 + 0.125, 1e-15);
    EXPECT_NEAR(c.integral(-0.5), -1.0 + 0.125, 1e-15);
    EXPECT_NEAR(c.integral(2.0), 2 * 1 + 0.5 + 3 * 1, 1e-15);
    EXPECT_NEAR(c.integral(-3.0), -(2 * 1 - 0.5 + 1 * 2), 1e-15);
    // The default curve is the constant 1; a constant c integrates to c t exactly.
    EXPECT_EQ(Curve()(123.0), 1.0);
    EXPECT_EQ(Curve().integral(0.7), 0.7);
    EXPECT_EQ(Curve::constant(2.095).integral(0.3), 2.095 * 0.3);
}

TEST(Curve, PulseStepAndPiecewiseConstantSchedules) {
    const Curve p = Curve::pulse(0.0, 0.2);
    EXPECT_EQ(p(-1e-9), 0.0);
    EXPECT_EQ(p(0.0), 1.0);
    EXPECT_EQ(p(std::nextafter(0.2, 0.0)), 1.0);
    EXPECT_EQ(p(0.2), 0.0);
    EXPECT_NEAR(p.integral(1.0), 0.2, 1e-16);
    const Curve r = Curve::pulse(0.0, 1.0, 0.25);
    EXPECT_EQ(r(0.125), 0.5);
    EXPECT_NEAR(r.integral(1.0), 0.75, 1e-15);
    const Curve g = Curve::step(0.5);
    EXPECT_EQ(g(std::nextafter(0.5, 0.0)), 0.0);
    EXPECT_EQ(g(0.5), 1.0);
    EXPECT_NEAR(g.integral(2.0), 1.5, 1e-15);
    // 2 rad/s, then 0.5 rad/s from 1.2 s, stopped at 1.5 s.
    const Curve s = Curve::steps({{0.0, 2.0}, {1.2, 0.5}, {1.5, 0.0}}, "drum speed");
    EXPECT_EQ(s(1.1999), 2.0);
    EXPECT_EQ(s(1.2), 0.5);
    EXPECT_EQ(s(1.5), 0.0);
    EXPECT_EQ(s(-1.0), 2.0);
    EXPECT_NEAR(s.integral(2.0), 2.4 + 0.15, 1e-15);
    EXPECT_EQ(s.name(), "drum speed");
}

TEST(Curve, BadPointsAreRefusedWithTheCurveName) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NE(test::input_error([] { Curve({{0, 0}, {1, 1}, {0.5, 2}}, "speed"); }).find("'speed'"), std::string::npos);
    EXPECT_NE(test::input_error([] { Curve({{0, 0}, {1, 1}, {1, 2}, {1, 3}}, "speed"); }).find("three points"), std::string::npos);
    EXPECT_THROW(Curve({}, "empty"), InputError);
    EXPECT_THROW(Curve({{0, nan}}, "nan"), InputError);
    EXPECT_THROW(Curve::steps({{0, 1}, {0, 2}}), InputError);
    EXPECT_THROW(Curve::pulse(1.0, 0.5), InputError);
}

// The curve seen from t0: c'(tau) = c(tau + t0) for a ramp, a step schedule and a constant; the
// points before t0 collapse into one at 0, so a shifted schedule is the schedule written from t0.
TEST(Curve, ShiftedIsTheCurveFromT0) {
    const Curve ramp({{0.0, 0.0}, {1.0, 2.0}, {3.0, 2.0}, {3.0, -1.0}, {4.0, 0.0}});
    for (double t0 : {0.0, 0.5, 1.0, 3.0, 5.0}) {
        const Curve s = ramp.shifted(t0);
        for (double tau : {0.0, 0.25, 0.5, 1.7, 2.5, 2.99, 3.5, 6.0})
            EXPECT_NEAR(s(tau), ramp(tau + t0), 1e-15) << "t0 " << t0 << " tau " << tau;
        EXPECT_NEAR(s.integral(2.0), ramp.integral(t0 + 2.0) - ramp.integral(t0), 1e-12) << "t0 " << t0;
    }
    const Curve steps = Curve::steps({{0.0, 0.4572}, {1.19, 0.254}});
    EXPECT_EQ(steps.shifted(0.95).points(), Curve::steps({{0.0, 0.4572}, {1.19 - 0.95, 0.254}}).points());
    EXPECT_EQ(Curve::constant(2.0).shifted(0.7).points(), Curve::constant(2.0).points());
    EXPECT_EQ(Curve().shifted(0.7)(3.0), 1.0);
}
