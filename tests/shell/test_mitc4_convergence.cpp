// MITC4 against closed forms: a thin cantilever (no shear locking down to t/L = 0.001), a simply
// supported square plate (Kirchhoff frequency) and a cantilever plate strip (Euler-Bernoulli
// frequency). Tolerances are set from the known accuracy of bilinear MITC4 on these meshes (a few
// tenths of a percent); a locking element misses by orders of magnitude.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "shell_test_model.hpp"

using namespace fem;
using namespace shelltest;
using std::numbers::pi;

namespace {
// nu = 0 in the beam comparisons, so that the strip bends like a beam (no anticlastic stiffening).
const ElasticMaterial kBeamSteel = ElasticMaterial::make("steel, nu 0", 210e9, 0.0, 7700);
const ElasticMaterial kPlateSteel = ElasticMaterial::make("steel", 210e9, 0.3, 7700);

// Cantilever strip L x b, nx x ny elements, clamped at x = 0. Optional distortion moves the interior
// node columns alternately by +-d (trapezoids) to test a distorted mesh.
DenseShellModel strip(double L, double b, int nx, int ny, double distortion = 0.0) {
    auto m = grid(L, b, nx, ny);
    for (auto& x : m.nodes) {
        const int i = static_cast<int>(std::lround(x.x() / L * nx));
        if (i > 0 && i < nx) x.x() += distortion * L / nx * (i % 2 ? 1 : -1) * (x.y() / b - 0.5) * 2;
    }
    return m;
}

std::vector<bool> clamp_x0(const DenseShellModel& m) {
    std::vector<bool> fixed(m.dofs(), false);
    for (int k = 0; k < static_cast<int>(m.nodes.size()); ++k)
        if (m.nodes[k].x() < 1e-12)
            for (int d = 0; d < 6; ++d) fixed[6 * k + d] = true;
    return fixed;
}

// Tip deflection under a total transverse tip load P spread consistently over the tip nodes.
double tip_deflection(DenseShellModel m, double L, double b, int ny, double t, double P) {
    m.assemble(t, kBeamSteel);
    Eigen::VectorXd f = Eigen::VectorXd::Zero(m.dofs());
    std::vector<int> tip;
    for (int k = 0; k < static_cast<int>(m.nodes.size()); ++k)
        if (m.nodes[k].x() > L - 1e-12) tip.push_back(k);
    for (int k : tip) {
        const bool edge = m.nodes[k].y() < 1e-12 || m.nodes[k].y() > b - 1e-12;
        f[6 * k + 2] = P / ny * (edge ? 0.5 : 1.0);
    }
    const Partition p(clamp_x0(m));
    const Eigen::VectorXd u = solve_static(m.K, f, p, Eigen::VectorXd::Zero(m.dofs()));
    double w = 0;
    for (int k : tip) w += u[6 * k + 2] / tip.size();
    return w;
}
}  // namespace

TEST(Mitc4Convergence, ThinCantileverDoesNotLock) {
    const double L = 1.0, b = 0.1, P = 1.0;
    const int nx = 16, ny = 2;
    double previous = 0;
    for (double ratio : {0.01, 0.001}) {
        const double t = ratio * L, I = b * t * t * t / 12;
        const double euler_bernoulli = P * L * L * L / (3 * kBeamSteel.youngs_modulus * I);
        const double w = tip_deflection(strip(L, b, nx, ny), L, b, ny, t, P);
        // Shear deformation adds 0.6 (t/L)^2 (Timoshenko, k = 5/6, nu = 0): < 1e-4 here.
        EXPECT_NEAR(w / euler_bernoulli, 1.0, 0.005) << "t/L = " << ratio;
        if (previous > 0) {
            EXPECT_NEAR(w / euler_bernoulli, previous, 1e-3) << "locking trend at t/L = " << ratio;
        }
        previous = w / euler_bernoulli;
        std::printf("  cantilever t/L = %g: w / w_EB = %.6f\n", ratio, w / euler_bernoulli);
    }
}

TEST(Mitc4Convergence, ThinCantileverOnDistortedMeshStillConverges) {
    // Trapezoidal elements (interior node columns skewed by +-0.4 element lengths across the width):
    // MITC4 loses some accuracy on distorted meshes but must not lock at t/L = 0.001.
    const double L = 1.0, b = 0.1, P = 1.0, t = 0.001, I = b * t * t * t / 12;
    const double euler_bernoulli = P * L * L * L / (3 * kBeamSteel.youngs_modulus * I);
    const double w = tip_deflection(strip(L, b, 16, 2, 0.4), L, b, 2, t, P);
    std::printf("  distorted cantilever t/L = 0.001: w / w_EB = %.6f\n", w / euler_bernoulli);
    EXPECT_NEAR(w / euler_bernoulli, 1.0, 0.03);
}

TEST(Mitc4Convergence, SimplySupportedSquarePlateFirstFrequency) {
    // Kirchhoff: omega_11 = 2 pi^2 / a^2 sqrt(D / (rho t)), D = E t^3 / (12 (1 - nu^2)); a/t = 100 so
    // the Mindlin (shear, rotary inertia) correction is below 0.1 %.
    const double a = 1.0, t = 0.01;
    const double D = kPlateSteel.youngs_modulus * t * t * t / (12 * (1 - 0.09));
    const double omega_exact = 2 * pi * pi / (a * a) * std::sqrt(D / (kPlateSteel.density * t));
    for (bool lumped : {false, true}) {
        auto m = grid(a, a, 12, 12);
        m.assemble(t, kPlateSteel, lumped);
        std::vector<bool> fixed(m.dofs(), false);
        for (int k = 0; k < static_cast<int>(m.nodes.size()); ++k) {
            const Vec3& x = m.nodes[k];
            const bool edge = x.x() < 1e-12 || x.y() < 1e-12 || x.x() > a - 1e-12 || x.y() > a - 1e-12;
            if (edge)
                for (int d = 0; d < 3; ++d) fixed[6 * k + d] = true;  // u = v = w = 0, rotations free
        }
        const Eigen::VectorXd w = natural_frequencies(m.K, m.M, Partition(fixed), 3);
        std::printf("  SS plate 12x12 %s mass: omega_1 / exact = %.5f, omega_2 / (2.5 exact) = %.5f\n",
                    lumped ? "lumped" : "consistent", w[0] / omega_exact, w[1] / (2.5 * omega_exact));
        EXPECT_NEAR(w[0] / omega_exact, 1.0, lumped ? 0.02 : 0.01);
        // Modes (1,2) and (2,1): a double frequency 5/2 omega_11 (coarser relative mesh: 3 %).
        EXPECT_NEAR(w[1] / (2.5 * omega_exact), 1.0, 0.03);
        EXPECT_NEAR(w[2] / w[1], 1.0, 1e-6);
    }
}

TEST(Mitc4Convergence, CantileverPlateFirstBendingFrequency) {
    // Euler-Bernoulli cantilever: omega_1 = 1.8751^2 sqrt(E I / (rho A L^4)).
    const double L = 0.5, b = 0.05, t = 0.002;
    const double I = b * t * t * t / 12, A = b * t;
    const double beta = 1.875104068711961;
    const double omega_exact =
        beta * beta * std::sqrt(kBeamSteel.youngs_modulus * I / (kBeamSteel.density * A * L * L * L * L));
    for (bool lumped : {false, true}) {
        auto m = strip(L, b, 20, 2);
        m.assemble(t, kBeamSteel, lumped);
        const Eigen::VectorXd w = natural_frequencies(m.K, m.M, Partition(clamp_x0(m)), 1);
        std::printf("  cantilever plate %s mass: omega_1 / beam theory = %.5f\n", lumped ? "lumped" : "consistent",
                    w[0] / omega_exact);
        EXPECT_NEAR(w[0] / omega_exact, 1.0, lumped ? 0.01 : 0.005);
    }
}
