// Verification of the lumped "Lagrange" bird (lib/multibody/lumped_bird.hpp): energy conservation,
// the linearised frequencies, a pendulum limit in closed form, the impulse equations at a jump of
// the shackle's velocity, and the shackle's motion itself.
#include <cmath>
#include <numbers>

#include <gsl/gsl_sf_ellint.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "multibody/lumped_bird.hpp"

using namespace fem;
using namespace fem::multibody;
using std::numbers::pi;

namespace {

// A bird of the size of the thesis's (1.69 kg, 75 mm shank) with springs of Table 5-2's order.
LumpedBird sample_bird() {
    LumpedBird b;
    b.m1 = 0.03, b.L1 = 0.075, b.c1 = 0.0375, b.I1 = 0.03 * 0.075 * 0.075 / 12.0;
    b.m2 = 1.6, b.l2 = 0.09, b.I2 = 1.6 * (0.097 * 0.097 + 0.057 * 0.057) / 5.0;
    b.k1 = 3.0, b.k2 = 5.0;
    b.rest1 = 14.0 * pi / 180.0, b.rest2 = 40.0 * pi / 180.0;
    b.body_point = Vec2(0.09, 0.0);
    return b;
}

double energy(const LumpedBirdSample& s) { return s.kinetic + s.potential; }

// Angular momentum about point p of the chain, absolute velocities, at a sample.
double angular_momentum(const LumpedBird& b, const LumpedBirdModel& m, const LumpedBirdState& s, const Vec2& p, bool link2_only) {
    auto cross = [](const Vec2& a, const Vec2& c) { return a.x() * c.y() - a.y() * c.x(); };
    const Vec2 base = m.motion().position(s.t), vb = m.motion().velocity(s.t);
    const Vec2 e1(std::cos(s.phi1), std::sin(s.phi1)), n1(-std::sin(s.phi1), std::cos(s.phi1));
    const Vec2 e2(std::cos(s.phi2), std::sin(s.phi2)), n2(-std::sin(s.phi2), std::cos(s.phi2));
    const Vec2 g1 = base + b.c1 * e1, g2 = base + b.L1 * e1 + b.l2 * e2;
    const Vec2 v1 = vb + b.c1 * s.dphi1 * n1, v2 = vb + b.L1 * s.dphi1 * n1 + b.l2 * s.dphi2 * n2;
    double h = b.m2 * cross(g2 - p, v2) + b.I2 * s.dphi2;
    if (!link2_only) h += b.m1 * cross(g1 - p, v1) + b.I1 * s.dphi1;
    return h;
}

}  // namespace

TEST(LumpedBird, EnergyIsConservedWithoutDampingAndBaseMotion) {
    LumpedBird b = sample_bird();
    const LumpedBirdModel model(b, ShackleMotion::fixed(Vec2(0.0, 0.0)));
    LumpedBirdState s = model.equilibrium(0.0, {0.0, b.rest1, b.rest1 + b.rest2, 0.0, 0.0});
    s.dphi1 = 3.0, s.dphi2 = -2.0;  // a large kick: the motion is far from linear
    const auto run = model.run(s, 2.0);
    const double e0 = energy(run.front());
    double worst = 0.0, scale = run.front().kinetic;
    for (const auto& r : run) worst = std::max(worst, std::abs(energy(r) - e0));
    EXPECT_LT(worst, 1e-8 * scale) << "kinetic energy at start " << scale;
}

TEST(LumpedBird, DampingOnlyRemovesEnergy) {
    LumpedBird b = sample_bird();
    b.alpha = 4.0;  // both modes underdamped (omega_1 = 8.3 rad/s): the energy decays like exp(-alpha t)
    const LumpedBirdModel model(b, ShackleMotion::fixed(Vec2(0.0, 0.0)));
    LumpedBirdState s = model.equilibrium(0.0, {0.0, b.rest1, b.rest1 + b.rest2, 0.0, 0.0});
    s.dphi1 = 3.0;
    const auto run = model.run(s, 5.0);
    for (std::size_t i = 1; i < run.size(); ++i) EXPECT_LE(energy(run[i]), energy(run[i - 1]) + 1e-12);
    EXPECT_LT(run.back().kinetic, 1e-6 * run.front().kinetic);
}

TEST(LumpedBird, SmallOscillationsHaveTheLinearisedFrequencies) {
    const LumpedBird b = sample_bird();
    const LumpedBirdModel model(b, ShackleMotion::fixed(Vec2(0.0, 0.0)));
    const LumpedBirdState eq = model.equilibrium(0.0, {0.0, b.rest1, b.rest1 + b.rest2, 0.0, 0.0});
    // The linearised eigenproblem K v = omega^2 M v, solved here independently (2 x 2 closed form).
    const double S1 = b.m1 * b.c1 + b.m2 * b.L1, S2 = b.m2 * b.l2;
    Eigen::Matrix2d K;
    K << -b.g * S1 * std::sin(eq.phi1) + b.k1 + b.k2, -b.k2, -b.k2, -b.g * S2 * std::sin(eq.phi2) + b.k2;
    const Eigen::Matrix2d M = model.mass_matrix(eq);
    // det(K - w2 M) = 0: a w2^2 + b w2 + c = 0.
    const double qa = M.determinant(), qb = -(K(0, 0) * M(1, 1) + K(1, 1) * M(0, 0) - 2.0 * K(0, 1) * M(0, 1)), qc = K.determinant();
    const double disc = std::sqrt(qb * qb - 4.0 * qa * qc);
    const Vec2 w2((-qb - disc) / (2.0 * qa), (-qb + disc) / (2.0 * qa));
    const Vec2 lib = model.linearised_omega_squared(eq);
    EXPECT_NEAR(lib.x(), w2.x(), 1e-10 * w2.x());
    EXPECT_NEAR(lib.y(), w2.y(), 1e-10 * w2.y());
    // Free vibration in each mode with a 1e-5 rad amplitude: the period from the upward zero
    // crossings of the modal coordinate over several periods.
    for (int mode = 0; mode < 2; ++mode) {
        const double omega2 = mode == 0 ? w2.x() : w2.y();
        Vec2 v = (K - omega2 * M).row(0).reverse();  // null vector of the singular 2 x 2
        v.x() = -v.x();
        v.normalize();
        LumpedBirdState s = eq;
        s.phi1 += 1e-5 * v.x();
        s.phi2 += 1e-5 * v.y();
        const double period = 2.0 * pi / std::sqrt(omega2);
        LumpedBirdOptions o;
        o.output_interval = period / 400.0;
        const auto run = model.run(s, 6.5 * period, o);
        std::vector<double> crossings;
        for (std::size_t i = 1; i < run.size(); ++i) {
            const double a = (run[i - 1].state.phi1 - eq.phi1) * v.x() + (run[i - 1].state.phi2 - eq.phi2) * v.y();
            const double c = (run[i].state.phi1 - eq.phi1) * v.x() + (run[i].state.phi2 - eq.phi2) * v.y();
            if (a < 0.0 && c >= 0.0) crossings.push_back(run[i - 1].state.t + (run[i].state.t - run[i - 1].state.t) * a / (a - c));
        }
        ASSERT_GE(crossings.size(), 5u);
        const double measured = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
        EXPECT_NEAR(measured, period, 2e-5 * period) << "mode " << mode + 1;
    }
}

TEST(LumpedBird, StiffKneeGivesTheCompoundPendulumPeriodInClosedForm) {
    // No spring at the paw, a very stiff one at J2: the chain swings about J1 as one rigid compound
    // pendulum, T = 4 K(sin(theta0 / 2)) / omega0, omega0^2 = M g d / I_J1, for a 60 degree amplitude.
    LumpedBird b = sample_bird();
    b.k1 = 0.0;
    b.rest2 = 0.5;
    const double S1 = b.m1 * b.c1, M = b.m1 + b.m2;
    // Rigid body: centre of mass and inertia about J1 with link 2 at phi2 = phi1 + rest2.
    const Vec2 g2(b.L1 + b.l2 * std::cos(b.rest2), b.l2 * std::sin(b.rest2));  // in link 1's frame
    const Vec2 com = (Vec2(S1, 0.0) + b.m2 * g2) / M;
    const double I = b.I1 + b.m1 * b.c1 * b.c1 + b.I2 + b.m2 * g2.squaredNorm();
    const double d = com.norm(), omega0 = std::sqrt(M * b.g * d / I);
    b.k2 = 1e5 * I * omega0 * omega0;  // knee frequency ~300 omega0: coupling error ~1e-5
    const LumpedBirdModel model(b, ShackleMotion::fixed(Vec2(0.0, 0.0)));
    // Hanging straight down (the COM below J1), then released from 60 degrees off.
    const double hang = -pi / 2.0 - std::atan2(com.y(), com.x()), amplitude = 60.0 * pi / 180.0;
    LumpedBirdState s;
    s.phi1 = hang + amplitude;
    s.phi2 = s.phi1 + b.rest2;
    // The static sag of the knee under gravity at the release angle is ~1e-5 rad: start from it.
    const double expected = 4.0 * gsl_sf_ellint_Kcomp(std::sin(amplitude / 2.0), GSL_PREC_DOUBLE) / omega0;
    LumpedBirdOptions o;
    o.output_interval = expected / 2000.0;
    const auto run = model.run(s, 3.2 * expected, o);
    // Period from the crossings of the swing angle through the hanging angle, moving upward.
    std::vector<double> crossings;
    for (std::size_t i = 1; i < run.size(); ++i) {
        const double a = run[i - 1].state.phi1 - hang, c = run[i].state.phi1 - hang;
        if (a < 0.0 && c >= 0.0) crossings.push_back(run[i - 1].state.t + (run[i].state.t - run[i - 1].state.t) * a / (a - c));
    }
    ASSERT_GE(crossings.size(), 3u);
    const double measured = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    EXPECT_NEAR(measured, expected, 2e-4 * expected) << "small-amplitude period " << 2.0 * pi / omega0;
}

TEST(LumpedBird, VelocityJumpConservesTheAngularMomenta) {
    // A jump of the paw's velocity is an impulse at J1: it cannot change the chain's angular momentum
    // about J1, nor link 2's about J2 (springs and gravity give no impulse). The chain starts at
    // rest, so both are zero right after the jump.
    const LumpedBird b = sample_bird();
    const LumpedBirdModel model(b, ShackleMotion::translation_step(Vec2(0.0, 0.0), Vec2(0.7, 0.2), 0.05));
    LumpedBirdState s{0.0, b.rest1 + 0.3, b.rest1 + b.rest2 - 0.2, 0.0, 0.0};
    LumpedBirdOptions o;
    o.output_interval = 0.01;
    const auto run = model.run(s, 0.06, o);
    const LumpedBirdState& after = run.front().state;  // t = 0, after the jump
    EXPECT_GT(std::abs(after.dphi1) + std::abs(after.dphi2), 1.0);
    const Vec2 j2 = Vec2(0.0, 0.0) + b.L1 * Vec2(std::cos(after.phi1), std::sin(after.phi1));
    EXPECT_NEAR(angular_momentum(b, model, after, Vec2(0.0, 0.0), false), 0.0, 1e-12);
    EXPECT_NEAR(angular_momentum(b, model, after, j2, true), 0.0, 1e-12);
    // The stop at t = 0.05 s: the momenta about the paw's (now fixed) position and about J2 keep
    // their values across the jump.
    std::size_t k = 0;
    while (run[k].state.t < 0.05 - 1e-12) ++k;  // the sample just after the stop
    const LumpedBirdState& stop = run[k].state;
    ASSERT_NEAR(stop.t, 0.05, 1e-12);
    LumpedBirdState before = stop;
    // Undo the jump: the state just before it satisfies the same momenta with the base still moving.
    const Vec2 paw = model.motion().position(0.05);
    const Vec2 j2s = paw + b.L1 * Vec2(std::cos(stop.phi1), std::sin(stop.phi1));
    const LumpedBirdModel moving(b, ShackleMotion::translation_step(Vec2(0.0, 0.0), Vec2(0.7, 0.2), 1.0));
    const auto pre = moving.run(s, 0.05, o);
    before = pre.back().state;
    ASSERT_NEAR(before.t, 0.05, 1e-12);
    EXPECT_NEAR(angular_momentum(b, model, stop, paw, false), angular_momentum(b, moving, before, paw, false), 1e-9);
    EXPECT_NEAR(angular_momentum(b, model, stop, j2s, true), angular_momentum(b, moving, before, j2s, true), 1e-9);
}

TEST(ShackleMotion, RotationStepTurnsThePawAboutThePivotThenStops) {
    const Vec2 pivot(0.1, 0.3), paw(-0.2, -0.1);
    const double rate = 8.73, duration = 0.116;
    const ShackleMotion m = ShackleMotion::rotation_step(paw, pivot, rate, duration);
    const double turned = rate * duration;
    EXPECT_NEAR(m.angle(0.2), turned, 1e-15);
    const Vec2 r = paw - pivot;
    const Vec2 expected = pivot + Vec2(std::cos(turned) * r.x() - std::sin(turned) * r.y(), std::sin(turned) * r.x() + std::cos(turned) * r.y());
    EXPECT_NEAR((m.position(0.3) - expected).norm(), 0.0, 1e-15);
    EXPECT_NEAR(m.velocity(0.05).norm(), rate * r.norm(), 1e-12);
    EXPECT_NEAR(m.velocity(0.05).dot(m.position(0.05) - pivot), 0.0, 1e-12);
    EXPECT_NEAR(m.acceleration(0.05).norm(), rate * rate * r.norm(), 1e-10);
    EXPECT_EQ(m.velocity(duration).norm(), 0.0);
    EXPECT_THROW(ShackleMotion::rotation_step(paw, pivot, rate, -1.0).validate(), InputError);
}

TEST(LumpedBird, RejectsASingularModel) {
    LumpedBird b = sample_bird();
    b.I2 = 0.0, b.l2 = 0.0;
    EXPECT_THROW(b.validate(), InputError);
    b = sample_bird();
    b.k1 = -1.0;
    EXPECT_THROW(b.validate(), InputError);
}
