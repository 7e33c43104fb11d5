// Rayleigh damping (Eq 2-45..2-47) and the SDOF oscillator (Eq 2-40, Table 2-7, Eq D-14, D-18)
// against closed forms and the thesis's printed example.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "damping/rayleigh.hpp"
#include "damping/sdof.hpp"

using namespace fem;
using namespace fem::damping;
using std::numbers::pi;

TEST(Rayleigh, ThesisExampleEq246And247) {
    // Sec 2.5.1: omega1 = 2 pi 10, omega2 = 2 pi 20, zeta1 = zeta2 = 0.1 -> alpha = 8.38 1/s, beta = 0.001 s.
    const auto c = rayleigh_from_two_modes(2 * pi * 10, 0.1, 2 * pi * 20, 0.1);
    // Printed precision: alpha to 2 decimals, beta to 3 decimals (half a unit of the last digit).
    EXPECT_NEAR(c.alpha, 8.38, 0.005);
    EXPECT_NEAR(c.beta, 0.001, 0.0005);
    // Equal ratios give the closed forms alpha = 2 zeta w1 w2 / (w1 + w2), beta = 2 zeta / (w1 + w2).
    EXPECT_NEAR(c.alpha, 2 * 0.1 * (2 * pi * 10) * (2 * pi * 20) / (2 * pi * 30), 1e-12);
    EXPECT_NEAR(c.beta, 2 * 0.1 / (2 * pi * 30), 1e-16);
}

TEST(Rayleigh, RoundTripAndMinimum) {
    const auto c = rayleigh_from_two_modes(3.0, 0.02, 50.0, 0.07);
    EXPECT_NEAR(rayleigh_damping_ratio(c, 3.0), 0.02, 1e-14);
    EXPECT_NEAR(rayleigh_damping_ratio(c, 50.0), 0.07, 1e-14);
    const double wmin = rayleigh_minimum_frequency(c);
    EXPECT_NEAR(rayleigh_damping_ratio(c, wmin), std::sqrt(c.alpha * c.beta), 1e-14);
    EXPECT_GT(rayleigh_damping_ratio(c, wmin * 1.01), rayleigh_damping_ratio(c, wmin));
    EXPECT_GT(rayleigh_damping_ratio(c, wmin * 0.99), rayleigh_damping_ratio(c, wmin));
    EXPECT_DOUBLE_EQ(mass_proportional_alpha(1.0, 16.33), 2 * 16.33);  // critical alpha = 2 omega
    EXPECT_THROW(rayleigh_from_two_modes(5, 0.1, 5, 0.1), InputError);
    EXPECT_THROW(rayleigh_damping_ratio(c, 0.0), InputError);
}

namespace {
// Residual of Eq 2-40 by central differences (step h), relative to omega_n^2 |x|max.
double ode_residual(const Sdof& s, double t, double h) {
    const double xm = s.displacement(t - h), x0 = s.displacement(t), xp = s.displacement(t + h);
    const double acc = (xp - 2 * x0 + xm) / (h * h), vel = (xp - xm) / (2 * h);
    return std::abs(acc + 2 * s.zeta * s.omega_n * vel + s.omega_n * s.omega_n * x0);
}
}  // namespace

TEST(Sdof, FreeResponseSolvesEq240InAllRegimes) {
    for (double zeta : {0.0, 0.05, 0.7, 1.0 - 1e-9, 1.0, 1.0 + 1e-9, 1.5, 8.0}) {
        const Sdof s{zeta, 7.0, 0.3, -2.0};
        EXPECT_NEAR(s.displacement(0.0), 0.3, 1e-15) << zeta;
        const double h = 1e-5;
        EXPECT_NEAR((s.displacement(h) - s.displacement(-h)) / (2 * h), -2.0, 1e-6) << zeta;
        // Central differences with h = 1e-4: truncation ~ h^2 |x''''| / 12 ~ 1e-8 w^4 x, round-off ~ 1e-16/h^2 ~ 1e-8.
        for (double t : {0.1, 0.3, 1.1, 2.9}) {
            EXPECT_LT(ode_residual(s, t, 1e-4), 1e-4) << zeta << " t " << t;
            // velocity() against a central difference of displacement() (h = 1e-5: error ~ h^2 w^3 x ~ 1e-7).
            const double h = 1e-5, fd = (s.displacement(t + h) - s.displacement(t - h)) / (2 * h);
            EXPECT_NEAR(s.velocity(t), fd, 1e-6) << zeta << " t " << t;
        }
        EXPECT_NEAR(s.velocity(0.0), -2.0, 1e-14) << zeta;
    }
    // Continuity across critical damping (the three closed forms must meet).
    const Sdof below{1.0 - 1e-7, 7.0, 0.3, -2.0}, at{1.0, 7.0, 0.3, -2.0}, above{1.0 + 1e-7, 7.0, 0.3, -2.0};
    for (double t : {0.1, 0.5, 2.0}) {
        EXPECT_NEAR(below.displacement(t), at.displacement(t), 1e-7);
        EXPECT_NEAR(above.displacement(t), at.displacement(t), 1e-7);
    }
    // Overdamped far out in time: the exponential branch (no cosh overflow) continues the cosh branch.
    const Sdof over{3.0, 10.0, 1.0, 0.0};
    const double g = 10.0 * std::sqrt(8.0), t_switch = 20.0 / g;
    EXPECT_NEAR(over.displacement(t_switch * (1 - 1e-9)) / over.displacement(t_switch * (1 + 1e-9)), 1.0, 1e-6);
    EXPECT_TRUE(std::isfinite(over.displacement(1e4)));
}

TEST(Sdof, TransferFunctionTable27) {
    // Table 2-7: zeta 0.0055, omega_n 16.33 rad/s, released from rest at x(0) = 55.5.
    const auto tf = transfer_function(Sdof{0.0055, 16.33, 55.5, 0.0});
    EXPECT_NEAR(tf.a1, 0.1796, 5e-5);  // printed to 4 decimals
    EXPECT_NEAR(tf.a0, 266.7, 0.05);
    EXPECT_NEAR(tf.b1, 55.5, 0.05);
    EXPECT_NEAR(tf.b0, 9.969, 5e-4);
    const Sdof back = sdof_from_transfer_function(tf);
    EXPECT_NEAR(back.zeta, 0.0055, 1e-15);
    EXPECT_NEAR(back.omega_n, 16.33, 1e-13);
    EXPECT_NEAR(back.v0, 0.0, 1e-13);
}

TEST(Sdof, TransferFunctionIsTheLaplaceTransformOfTheResponse) {
    // X(s) at real s = 3 by the trapezoid rule on the closed-form response (step 1e-4 over 20 s,
    // where e^{-3t} has fallen to 1e-26): error ~ h^2 / 12 |f''| ~ 1e-8 relative.
    const Sdof s{0.2, 5.0, 1.3, 0.7};
    const auto tf = transfer_function(s);
    const double sv = 3.0, h = 1e-4;
    double sum = 0.5 * s.displacement(0);
    for (int i = 1; i < 200000; ++i) sum += s.displacement(i * h) * std::exp(-sv * i * h);
    sum *= h;
    const double expected = (tf.b1 * sv + tf.b0) / (sv * sv + tf.a1 * sv + tf.a0);
    EXPECT_NEAR(sum / expected, 1.0, 1e-6);
}

TEST(Sdof, MagnificationFactorAndHalfPowerPoints) {
    for (double zeta : {0.01, 0.1, 0.3}) {
        EXPECT_NEAR(magnification_factor(1.0, zeta), 1.0 / (2 * zeta), 1e-12);  // Eq D-20
        // Eq D-14 points satisfy Eq D-12: D_s = D_s(r = 1) / sqrt 2.
        const auto r = half_power_ratios(zeta);
        EXPECT_NEAR(magnification_factor(r.r1, zeta), 1.0 / (2 * zeta * std::sqrt(2.0)), 1e-10);
        EXPECT_NEAR(magnification_factor(r.r2, zeta), 1.0 / (2 * zeta * std::sqrt(2.0)), 1e-10);
        // The measured points are relative to the true peak 1 / (2 zeta sqrt(1 - zeta^2)).
        const auto p = peak_half_power_ratios(zeta);
        const double peak = 1.0 / (2 * zeta * std::sqrt(1 - zeta * zeta));
        EXPECT_NEAR(magnification_factor(p.r1, zeta), peak / std::sqrt(2.0), 1e-9 * peak);
        EXPECT_NEAR(magnification_factor(p.r2, zeta), peak / std::sqrt(2.0), 1e-9 * peak);
    }
    EXPECT_TRUE(std::isnan(half_power_ratios(0.4).r1));       // D-14 lower root gone above ~0.354
    EXPECT_TRUE(std::isnan(peak_half_power_ratios(0.39).r1)); // measured lower point gone above sin(pi/8)
    EXPECT_FALSE(std::isnan(peak_half_power_ratios(0.38).r1));
    // Peak of D_s above r = 0 exists only for zeta < 1/sqrt 2 (Fig D-4: "greater than 0.7, no peak").
    const double zc = max_zeta_with_resonance_peak();
    EXPECT_GT(magnification_factor(0.2, zc * 0.98), magnification_factor(0.0, zc * 0.98));
    EXPECT_LT(magnification_factor(0.2, zc * 1.02), magnification_factor(0.0, zc * 1.02));
    // Eq D-17's estimate: zeta (1 + O(zeta^2)).
    EXPECT_NEAR(half_power_estimate(0.005) / 0.005, 1.0, 1e-4);
    EXPECT_GT(half_power_estimate(0.1) / 0.1, 1.015);
}
