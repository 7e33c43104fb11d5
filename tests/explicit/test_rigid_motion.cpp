// Rigid motions (explicit/rigid_motion.hpp): positions against closed forms, analytic velocities
// against finite differences of the positions and against closed forms, composition.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "core/error.hpp"
#include "explicit/rigid_motion.hpp"
#include "explicit_test_support.hpp"

using namespace fem;
using namespace fem::test;
using std::numbers::pi;

namespace {
// Central difference of the position (h = 1e-6: truncation ~ h^2 |x'''|, round-off ~ 1e-16 / h).
Vec3 fd_velocity(const RigidMotion& m, const Vec3& X, double t) {
    const double h = 1e-6;
    return (m.position(X, t + h) - m.position(X, t - h)) / (2 * h);
}
// Spatial angular velocity from the rotation: skew(omega) = R' R^T (central difference).
Vec3 fd_omega(const RigidMotion& m, double t) {
    const double h = 1e-6;
    const Mat3 W = (m.pose(t + h).R - m.pose(t - h).R) / (2 * h) * m.pose(t).R.transpose();
    return Vec3(W(2, 1), W(0, 2), W(1, 0));
}
}  // namespace

// omega ramps 0 -> 2 rad/s over 1 s, then holds: angle t^2 (t <= 1), 1 + 2 (t - 1) after.
TEST(RigidMotion, RotationAboutAnAxisWithRampedSpeed) {
    const Vec3 c(1, 2, 0);
    const RigidMotion m = RigidMotion::rotation(c, Vec3(0, 0, 2), Curve({{0, 0}, {1, 2}}));
    const Vec3 X(2, 2, 0.5);
    EXPECT_NEAR((m.position(X, 0.5) - (c + Vec3(std::cos(0.25), std::sin(0.25), 0.5))).norm(), 0.0, 1e-15);
    EXPECT_NEAR((m.position(X, 2.0) - (c + Vec3(std::cos(3.0), std::sin(3.0), 0.5))).norm(), 0.0, 1e-14);
    for (double t : {0.3, 1.5}) {
        EXPECT_NEAR((m.velocity(X, t) - fd_velocity(m, X, t)).norm(), 0.0, 1e-8) << t;
        const Vec3 x = m.position(X, t);  // closed form: omega e_z x (x - c)
        EXPECT_NEAR((m.velocity(X, t) - Vec3(0, 0, t <= 1 ? 2 * t : 2.0).cross(x - c)).norm(), 0.0, 1e-14) << t;
    }
    EXPECT_EQ(m.position(X, 0.0), X);
    EXPECT_TRUE(RigidMotion::fixed().is_fixed());
    EXPECT_EQ(RigidMotion::fixed().position(X, 3.0), X);
    EXPECT_THROW(RigidMotion::rotation(c, Vec3::Zero(), {}), InputError);
}

// A pallet moving at 0.5 m/s along x, stopped at 1 s and moved on at 0.2 m/s from 1.5 s.
TEST(RigidMotion, TranslationWithASpeedScheduleWithSteps) {
    const RigidMotion m = RigidMotion::translation(Vec3(0.5, 0, 0), Curve::steps({{0, 1}, {1, 0}, {1.5, 0.4}}));
    const Vec3 X(0.1, 0.2, 0.3);
    EXPECT_NEAR((m.position(X, 0.6) - (X + Vec3(0.3, 0, 0))).norm(), 0.0, 1e-16);
    EXPECT_NEAR((m.position(X, 1.2) - (X + Vec3(0.5, 0, 0))).norm(), 0.0, 1e-16);
    EXPECT_NEAR((m.position(X, 2.0) - (X + Vec3(0.6, 0, 0))).norm(), 0.0, 1e-15);
    EXPECT_EQ(m.velocity(X, 0.6), Vec3(0.5, 0, 0));
    EXPECT_EQ(m.velocity(X, 1.0), Vec3::Zero());  // at a step: the later value
    EXPECT_EQ(m.velocity(X, 1.7), Vec3(0.2, 0, 0));
    EXPECT_EQ(m.angular_velocity(1.7), Vec3::Zero());
}

// The flip of thesis Sec 4.4: the drum spins about its own axis (through c_d along a_d) at w until
// it has turned 180 degrees, then the whole hand turns 135 degrees about the global z axis through
// the origin at 4.71 rad/s for 0.5 s. One RigidMotion, compose(flip, drum); every position equals
// the closed form, and velocities equal the analytic rigid-body fields and the differences.
TEST(RigidMotion, DrumSpinThenHandFlipIsOneComposedMotion) {
    const Vec3 cd(0.1, -0.05, 0.02), ad = Vec3(1, 0, 0.2).normalized();
    const double w = 2.095, t_stop = pi / w, t_flip = 1.5, w_flip = 4.71;
    ASSERT_LT(t_stop, t_flip);
    const RigidMotion drum = RigidMotion::rotation(cd, ad, Curve::steps({{0, w}, {t_stop, 0}}, "drum"));
    const RigidMotion flip =
        RigidMotion::rotation(Vec3::Zero(), Vec3::UnitZ(), Curve::steps({{0, 0}, {t_flip, w_flip}, {t_flip + 0.5, 0}}));
    const RigidMotion hand = compose(flip, drum);
    const Vec3 X(0.15, 0.02, -0.03);
    const auto drum_x = [&](double t) { return Vec3(cd + rotation(w * std::min(t, t_stop), ad) * (X - cd)); };
    const auto flip_angle = [&](double t) { return w_flip * std::clamp(t - t_flip, 0.0, 0.5); };
    for (double t : {0.0, 0.4, 1.0, t_stop, 1.6, 1.8, 2.0, 2.7}) {
        const Vec3 closed = rotation(flip_angle(t), Vec3::UnitZ()) * drum_x(t);
        EXPECT_NEAR((hand.position(X, t) - closed).norm(), 0.0, 2e-16 * 16) << t;
    }
    // 135 degrees at the end, about z: the drum axis has turned with the hand.
    EXPECT_NEAR(flip_angle(2.7), 0.75 * pi, 2e-3);  // 4.71 x 0.5 = 2.355 = 135 degrees (4.71 ~ 3 pi / 2)
    const Vec3 ad_end = hand.pose(2.7).R * ad;
    EXPECT_NEAR((ad_end - rotation(flip_angle(2.7), Vec3::UnitZ()) * ad).norm(), 0.0, 1e-15);
    // Velocities: the drum spinning alone, then the hand turning with the drum stopped.
    for (double t : {0.4, 1.0}) {
        const Vec3 x = hand.position(X, t);
        EXPECT_NEAR((hand.velocity(X, t) - w * ad.cross(x - cd)).norm(), 0.0, 1e-15) << t;
        EXPECT_NEAR((hand.angular_velocity(t) - w * ad).norm(), 0.0, 1e-15);
    }
    for (double t : {1.6, 1.9}) {
        const Vec3 x = hand.position(X, t);
        EXPECT_NEAR((hand.velocity(X, t) - w_flip * Vec3::UnitZ().cross(x)).norm(), 0.0, 1e-15) << t;
    }
    EXPECT_EQ(hand.velocity(X, 2.7), Vec3::Zero());
    for (double t : {0.4, 1.0, 1.6, 1.9})
        EXPECT_NEAR((hand.velocity(X, t) - fd_velocity(hand, X, t)).norm(), 0.0, 1e-8) << t;
}

// Both spinning at once, plus a translation outermost, with ramped speeds: the analytic twist of
// the composition equals the differences of the positions and of the rotation, at several points.
TEST(RigidMotion, CompositionVelocitiesMatchFiniteDifferences) {
    const RigidMotion inner = RigidMotion::rotation(Vec3(0.3, 0.1, 0), Vec3(0, 1, 1), Curve({{0, 1}, {2, 3}}));
    const RigidMotion middle = RigidMotion::rotation(Vec3(-0.2, 0, 0.5), Vec3(1, 0, 0), Curve({{0, -2}, {1, 0.5}}));
    const RigidMotion outer = RigidMotion::translation(Vec3(0.1, -0.3, 0.2), Curve({{0, 0}, {1, 1}, {2, -1}}));
    const RigidMotion m = inner.then(middle).then(outer);
    for (double t : {0.2, 0.77, 1.3}) {
        const Vec3 w = m.angular_velocity(t);
        EXPECT_NEAR((w - fd_omega(m, t)).norm(), 0.0, 1e-8) << t;
        for (const Vec3& X : {Vec3(0, 0, 0), Vec3(1, 2, 3), Vec3(-0.5, 0.3, 0.1)}) {
            EXPECT_NEAR((m.velocity(X, t) - fd_velocity(m, X, t)).norm(), 0.0, 1e-8) << t;
            // velocity_at(x) is the velocity of the body point at x (a rigid field).
            const Vec3 x = m.position(X, t);
            EXPECT_NEAR((m.velocity_at(x, t) - m.velocity(X, t)).norm(), 0.0, 1e-15);
        }
        // compose(outer, inner) is inner.then(outer).
        const Vec3 X(0.4, -0.1, 0.2);
        EXPECT_EQ(compose(outer, inner.then(middle)).position(X, t), m.position(X, t));
    }
}

// The perch of thesis Table 5-6 on its conveyor: 0.4741 m/s inclined 5 degrees up to the apex at
// 0.7 s, then declined 30 degrees (the x sign: travel toward the drum, THESIS_CH4_5.md
// reconstruction 15). Exact positions at and between the corners, the later velocity at a corner,
// at rest before the first segment, and bad input refused.
TEST(RigidMotion, PiecewiseTranslationIsThePerchPathOfTable56) {
    const Vec3 v1(-0.4723, 0.04132, 0), v2(-0.4105, -0.23705, 0);
    EXPECT_NEAR(v1.norm(), 0.4741, 1e-4);  // the printed conveyor speed, at 5.0 and 30.0 degrees
    EXPECT_NEAR(v2.norm(), 0.4741, 1e-4);
    EXPECT_NEAR(std::atan2(v1.y(), -v1.x()) * 180 / pi, 5.0, 0.01);
    EXPECT_NEAR(std::atan2(-v2.y(), -v2.x()) * 180 / pi, 30.0, 0.01);
    const RigidMotion perch = RigidMotion::piecewise_translation({{0.0, v1}, {0.7, v2}}, "perch");
    const Vec3 top(0.387, -0.039, 0.184);  // Table 5-6: perch top centre at t = 0
    EXPECT_EQ(perch.position(top, 0.0), top);
    EXPECT_NEAR((perch.position(top, 0.35) - (top + 0.35 * v1)).norm(), 0.0, 1e-15);
    const Vec3 apex = top + 0.7 * v1;
    EXPECT_NEAR((perch.position(top, 0.7) - apex).norm(), 0.0, 1e-15);
    // THESIS_CH4_5.md inconsistency 6: the apex is 56.4 mm from the drum centre, not 2 in (50.8).
    EXPECT_NEAR(apex.x(), 0.0564, 1e-4);
    EXPECT_NEAR((perch.position(top, 0.9) - (apex + 0.2 * v2)).norm(), 0.0, 1e-15);
    EXPECT_NEAR((perch.position(top, 1.1) - (apex + 0.4 * v2)).norm(), 0.0, 1e-15);  // the last segment held
    EXPECT_EQ(perch.velocity(top, 0.3), v1);
    EXPECT_EQ(perch.velocity(top, 0.7), v2);  // at a corner: the later velocity
    EXPECT_EQ(perch.velocity(top, 1.05), v2);
    EXPECT_EQ(perch.angular_velocity(0.8), Vec3::Zero());
    for (double t : {0.2, 0.69, 0.71, 0.95}) EXPECT_NEAR((perch.velocity(top, t) - fd_velocity(perch, top, t)).norm(), 0.0, 1e-9) << t;

    // Starting later: at rest before the first time; three segments.
    const RigidMotion late = RigidMotion::piecewise_translation({{0.5, Vec3(1, 0, 0)}, {1.0, Vec3(0, 2, 0)}, {1.5, Vec3::Zero()}});
    EXPECT_EQ(late.position(top, 0.4), top);
    EXPECT_NEAR((late.position(top, 2.0) - (top + Vec3(0.5, 1.0, 0))).norm(), 0.0, 1e-15);

    EXPECT_THROW(RigidMotion::piecewise_translation({}), InputError);
    EXPECT_THROW(RigidMotion::piecewise_translation({{0.7, v1}, {0.7, v2}}), InputError);
    EXPECT_THROW(RigidMotion::piecewise_translation({{0.0, v1}, {std::nan(""), v2}}), InputError);
    EXPECT_THROW(RigidMotion::piecewise_translation({{0.0, Vec3(INFINITY, 0, 0)}}), InputError);
}
