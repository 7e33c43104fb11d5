// Unit tests of the mode-shape classifier (lib/modal/mode_classification): analytic displacement
// fields of a slender elliptic cylinder (the finger of thesis Table 3-1, 12 x 8.45 mm, 203 mm long)
// whose type is known by construction: cantilever bending in either plane (with the Euler-Bernoulli
// section rotations), Saint-Venant torsion (with warping), elongation, cross-section breathing, and
// mixtures.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "modal/mode_classification.hpp"

using namespace fem;
using namespace fem::modal;
using std::numbers::pi;

namespace {

constexpr double kFingerA = 0.012, kFingerB = 0.00845, kFingerL = 0.2032;

// Nodes of an elliptic cylinder: rings of points on scaled ellipses, irregular in z (a random
// jitter, as tet10 nodes are) so that slices do not line up with node layers.
std::vector<Vec3> cylinder_nodes() {
    std::vector<Vec3> x;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-0.4, 0.4);
    const int layers = 80;
    for (int k = 0; k <= layers; ++k) {
        x.emplace_back(0, 0, kFingerL * k / layers);
        for (int r = 1; r <= 3; ++r)
            for (int j = 0; j < 8 * r; ++j) {
                const double phi = 2 * pi * j / (8 * r), s = r / 3.0;
                double z = kFingerL * (k + (k > 0 && k < layers ? jitter(rng) : 0.0)) / layers;
                x.emplace_back(s * kFingerA * std::cos(phi), s * kFingerB * std::sin(phi), z);
            }
    }
    return x;
}

// First cantilever bending shape (Euler-Bernoulli), lambda = 1.8751.
double bend(double z) {
    const double l = 1.8751 / kFingerL, s = (std::cosh(l * kFingerL) + std::cos(l * kFingerL)) / (std::sinh(l * kFingerL) + std::sin(l * kFingerL));
    return std::cosh(l * z) - std::cos(l * z) - s * (std::sinh(l * z) - std::sin(l * z));
}
double bend_slope(double z) {
    const double l = 1.8751 / kFingerL, s = (std::cosh(l * kFingerL) + std::cos(l * kFingerL)) / (std::sinh(l * kFingerL) + std::sin(l * kFingerL));
    return l * (std::sinh(l * z) + std::sin(l * z) - s * (std::cosh(l * z) - std::cos(l * z)));
}

// Bending in the y-z plane: v = f(z) along y, w = -y f'(z) (plane sections stay plane).
std::vector<Vec3> bending_y(const std::vector<Vec3>& x) {
    std::vector<Vec3> u;
    for (const Vec3& p : x) u.emplace_back(0, bend(p.z()), -p.y() * bend_slope(p.z()));
    return u;
}
std::vector<Vec3> bending_x(const std::vector<Vec3>& x) {
    std::vector<Vec3> u;
    for (const Vec3& p : x) u.emplace_back(bend(p.z()), 0, -p.x() * bend_slope(p.z()));
    return u;
}
// First torsion mode of a clamped bar: theta = sin(pi z / 2L), with the elliptic warping
// w = theta' (b^2 - a^2)/(a^2 + b^2) x y.
std::vector<Vec3> torsion(const std::vector<Vec3>& x) {
    std::vector<Vec3> u;
    for (const Vec3& p : x) {
        const double th = std::sin(pi * p.z() / (2 * kFingerL)), dth = pi / (2 * kFingerL) * std::cos(pi * p.z() / (2 * kFingerL));
        u.emplace_back(-th * p.y(), th * p.x(), dth * (kFingerB * kFingerB - kFingerA * kFingerA) / (kFingerA * kFingerA + kFingerB * kFingerB) * p.x() * p.y());
    }
    return u;
}
// First axial mode with the Poisson contraction of nu = 0.49.
std::vector<Vec3> elongation(const std::vector<Vec3>& x) {
    std::vector<Vec3> u;
    for (const Vec3& p : x) {
        const double w = std::sin(pi * p.z() / (2 * kFingerL)), dw = pi / (2 * kFingerL) * std::cos(pi * p.z() / (2 * kFingerL));
        u.emplace_back(-0.49 * dw * p.x(), -0.49 * dw * p.y(), w);
    }
    return u;
}
// Cross-section breathing (radial in-plane motion): no rigid-section part.
std::vector<Vec3> breathing(const std::vector<Vec3>& x) {
    std::vector<Vec3> u;
    for (const Vec3& p : x) u.emplace_back(p.x(), p.y(), 0);
    return u;
}

std::vector<Vec3> combine(const std::vector<Vec3>& a, double ca, const std::vector<Vec3>& b, double cb) {
    std::vector<Vec3> u(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) u[i] = ca * a[i] + cb * b[i];
    return u;
}

double sum(const ModeClassification& c) { return c.bending + c.torsion + c.elongation + c.other; }

}  // namespace

TEST(ModeClassification, BendingInEachPlane) {
    const auto x = cylinder_nodes();
    const auto cy = classify_mode(x, bending_y(x), {});
    EXPECT_EQ(cy.type, ModeType::Bending);
    EXPECT_EQ(cy.bending_direction, 2);  // e1 = x, so y is e2
    EXPECT_GT(cy.bending, 0.99);         // plane sections: all but slice-thickness misfit
    EXPECT_NEAR(sum(cy), 1.0, 1e-12);
    EXPECT_EQ(cy.label(), "bending (e2)");
    const auto cx = classify_mode(x, bending_x(x), {});
    EXPECT_EQ(cx.type, ModeType::Bending);
    EXPECT_EQ(cx.bending_direction, 1);
    EXPECT_GT(cx.bending_e1, 0.99);
    EXPECT_LT(cx.bending_e2, 1e-10);
}

TEST(ModeClassification, TorsionWithWarping) {
    const auto x = cylinder_nodes();
    const auto c = classify_mode(x, torsion(x), {});
    EXPECT_EQ(c.type, ModeType::Torsion);
    EXPECT_GT(c.torsion, 0.95);  // the warping (a few %) is not a rigid-section motion: "other"
    // Nodes jittered in z within a slice see different twists, so a slice's rotation field is not
    // exactly symmetric: a small spurious translation (well under 1 %) remains.
    EXPECT_LT(c.bending, 0.01);
    EXPECT_EQ(c.label(), "torsion");
}

TEST(ModeClassification, ElongationWithPoissonContraction) {
    const auto x = cylinder_nodes();
    const auto c = classify_mode(x, elongation(x), {});
    EXPECT_EQ(c.type, ModeType::Elongation);
    EXPECT_GT(c.elongation, 0.95);
    EXPECT_LT(c.torsion, 1e-10);
}

TEST(ModeClassification, BreathingIsOther) {
    const auto x = cylinder_nodes();
    const auto c = classify_mode(x, breathing(x), {});
    EXPECT_EQ(c.type, ModeType::Other);
    EXPECT_GT(c.other, 0.99);
}

TEST(ModeClassification, MixtureSplitsByEnergy) {
    // Mass-orthogonal fields: the fractions of a mixture follow the squared amplitudes.
    const auto x = cylinder_nodes();
    const auto b = bending_y(x), t = torsion(x);
    const auto cb = classify_mode(x, b, {}), ct = classify_mode(x, t, {});
    double nb = 0, nt = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        nb += b[i].squaredNorm();
        nt += t[i].squaredNorm();
    }
    // Scale torsion so that it holds 70 % of the energy.
    const double s = std::sqrt(0.7 / 0.3 * nb / nt);
    const auto c = classify_mode(x, combine(b, 1.0, t, s), {});
    EXPECT_EQ(c.type, ModeType::Torsion);
    EXPECT_NEAR(c.torsion, 0.7 * ct.torsion, 0.02);
    EXPECT_NEAR(c.bending, 0.3 * cb.bending, 0.02);
}

TEST(ModeClassification, RotatedFrameAndWeights) {
    // The same bending field expressed in a rotated frame (axis along x): the classification follows
    // the options, and uniform weights change nothing.
    const auto x0 = cylinder_nodes();
    const auto u0 = bending_y(x0);
    Mat3 R;
    R << 0, 0, 1, 1, 0, 0, 0, 1, 0;  // z -> x, x -> y, y -> z
    std::vector<Vec3> x, u;
    for (std::size_t i = 0; i < x0.size(); ++i) {
        x.push_back(R * x0[i] + Vec3(1, 2, 3));
        u.push_back(R * u0[i]);
    }
    ModeClassificationOptions o;
    o.origin = Vec3(1, 2, 3);
    o.axis = Vec3(2, 0, 0);
    o.transverse = Vec3(0, 1, 0);
    const std::vector<double> w(x.size(), 3.5);
    const auto c = classify_mode(x, u, w, o);
    const auto c0 = classify_mode(x0, u0, {});
    EXPECT_EQ(c.type, ModeType::Bending);
    EXPECT_EQ(c.bending_direction, 2);
    // Same slices up to round-off in the bin boundaries (a node on a boundary may change slice).
    EXPECT_NEAR(c.bending, c0.bending, 1e-5);
}

TEST(ModeClassification, FlatOverloadMatches) {
    const auto x = cylinder_nodes();
    const auto u = torsion(x);
    std::vector<double> flat;
    for (const Vec3& v : u) flat.insert(flat.end(), {v.x(), v.y(), v.z()});
    const auto a = classify_mode(x, std::span<const double>(flat), {}), b = classify_mode(x, u, {});
    EXPECT_EQ(a.type, b.type);
    EXPECT_DOUBLE_EQ(a.torsion, b.torsion);
}

TEST(ModeClassification, BadInputNamesTheProblem) {
    const auto x = cylinder_nodes();
    auto u = bending_y(x);
    EXPECT_THROW(classify_mode(x, std::vector<Vec3>(3, Vec3::Zero()), {}), InputError);
    EXPECT_THROW(classify_mode(x, std::vector<Vec3>(x.size(), Vec3::Zero()), {}), InputError);
    EXPECT_THROW(classify_mode(x, u, std::vector<double>(2, 1.0)), InputError);
    std::vector<double> w(x.size(), 1.0);
    w[5] = -1.0;
    EXPECT_THROW(classify_mode(x, u, w), InputError);
    ModeClassificationOptions o;
    o.axis = Vec3::Zero();
    EXPECT_THROW(classify_mode(x, u, {}, o), InputError);
    o.axis = Vec3::UnitZ();
    o.transverse = Vec3(0, 0, 2);
    EXPECT_THROW(classify_mode(x, u, {}, o), InputError);
    try {
        classify_mode(x, std::vector<double>(5, 0.0), {});
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("3 per node"), std::string::npos);
    }
}
