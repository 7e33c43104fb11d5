// Verification of the corotational beam (element/beam_corotational.hpp) and of the point mass:
// rigid rotations without strain, the linear Euler-Bernoulli stiffness at small deformation,
// cantilever frequencies without and with a tip mass (thesis Sec 2.5.3 setting), and a free spin.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "explicit_test_support.hpp"
#include "core/error.hpp"
#include "element/beam_corotational.hpp"
#include "explicit/solver.hpp"

using namespace fem;
using namespace fem::test;
using fem::test::quiet;

namespace {




// Root lambda of the cantilever-with-tip-mass frequency equation (mass ratio r = M / (rho A L)):
// 1 + cos l cosh l + r l (cos l sinh l - sin l cosh l) = 0, first root, by bisection.
double tip_mass_lambda(double r) {
    auto f = [r](double l) {
        return 1 + std::cos(l) * std::cosh(l) + r * l * (std::cos(l) * std::sinh(l) - std::sin(l) * std::cosh(l));
    };
    double a = 0.3, b = 1.8751040687;
    for (int i = 0; i < 200; ++i) {
        const double m = 0.5 * (a + b);
        (f(a) * f(m) <= 0 ? b : a) = m;
    }
    return 0.5 * (a + b);
}
}  // namespace

TEST(BeamKernel, LargeRigidRotationCreatesNoForce) {
    const auto s = beam::Section::circular(0.6e-3);
    const Vec3 a(0.1, 0.2, 0.3), b(0.104, 0.2, 0.3);
    const auto ref = beam::make_reference(a, b);
    beam::Result r;
    for (double deg : {45.0, 90.0, 180.0, 270.0}) {
        const Mat3 R = rotation(deg * kPi / 180, Vec3(0.3, -1, 2));
        const Vec3 shift(1, -2, 0.5);
        beam::internal_force(ref, s, kWireSteel, R * a + shift, R * b + shift, R, R, r);
        EXPECT_LT(std::abs(r.strain_energy), 1e-18) << deg;
        // Round-off only: EA = 5.9e4 N times the round-off of the strain of a 4 mm element 2 m from
        // the origin (~1e-13) gives ~1e-8 N (a first guess of 1e-9 N was below round-off); a beam with
        // linear kinematics would give ~EA = 1e4 N here. Moments: EI/L = 0.33 N m times ~1e-13.
        for (int i = 0; i < 2; ++i) {
            EXPECT_LT(r.force[i].norm(), 1e-12 * kWireSteel.youngs_modulus * s.area) << deg;
            EXPECT_LT(r.moment[i].norm(), 1e-12) << deg;
        }
    }
}

TEST(BeamKernel, SmallDeformationGivesEulerBernoulliStiffness) {
    const auto s = beam::Section::circular(2e-3);
    const double L = 0.05, th = 1e-6, du = 1e-9;
    const auto ref = beam::make_reference(Vec3::Zero(), Vec3(L, 0, 0), Vec3(0, 1, 0));
    beam::Result r;
    const double EI = kWireSteel.youngs_modulus * s.iz;
    // Rotate node 2 by theta about z: M1 = 2EI/L theta, M2 = 4EI/L theta, shear 6EI/L^2 theta.
    beam::internal_force(ref, s, kWireSteel, Vec3::Zero(), Vec3(L, 0, 0), Mat3::Identity(), rotation(th, Vec3::UnitZ()), r);
    EXPECT_NEAR(r.moment[0].z(), 2 * EI / L * th, 1e-6 * 2 * EI / L * th);
    EXPECT_NEAR(r.moment[1].z(), 4 * EI / L * th, 1e-6 * 4 * EI / L * th);
    EXPECT_NEAR(r.force[1].y(), -6 * EI / (L * L) * th, 1e-6 * 6 * EI / (L * L) * th);
    EXPECT_NEAR(r.strain_energy, 2 * EI / L * th * th, 1e-5 * 2 * EI / L * th * th);
    // Axial: N = EA du / L.
    beam::internal_force(ref, s, kWireSteel, Vec3::Zero(), Vec3(L + du, 0, 0), Mat3::Identity(), Mat3::Identity(), r);
    EXPECT_NEAR(r.force[1].x(), kWireSteel.youngs_modulus * s.area * du / L, 1e-5 * kWireSteel.youngs_modulus * s.area * du / L);
    // Torsion: T = GJ phi / L.
    beam::internal_force(ref, s, kWireSteel, Vec3::Zero(), Vec3(L, 0, 0), Mat3::Identity(), rotation(th, Vec3::UnitX()), r);
    EXPECT_NEAR(r.moment[1].x(), kWireSteel.shear_modulus() * s.torsion * th / L, 1e-6 * kWireSteel.shear_modulus() * s.torsion * th / L);
}

TEST(BeamKernel, RotationalInertiaScalingKeepsTheAxialStep) {
    // Table 2-8 element: L = 4 mm, d = 0.6 mm. The step must be the Table 2-1 beam value L/c.
    const auto s = beam::Section::circular(0.6e-3);
    const double L = 0.004, c = std::sqrt(kWireSteel.youngs_modulus / kWireSteel.density);
    EXPECT_NEAR(beam::critical_time_step(s, kWireSteel, Vec3::Zero(), Vec3(L, 0, 0)), L / c, 1e-12 * L / c);
    EXPECT_GE(beam::nodal_rotational_inertia(s, kWireSteel, L), beam::physical_rotational_inertia(s, kWireSteel, L));
}

namespace {
struct BeamRun {
    double omega = 0;
    RunSummary summary;
};

// Cantilever of n beam elements, clamped at x = 0, optional tip mass, started by a tip force held
// for a short time then released (free vibration), frequency from zero crossings of the tip.
BeamRun cantilever(double L, double d, int n, double tip_mass, double periods, double T_guess) {
    Mesh mesh = line_beam2(Vec3::Zero(), Vec3(L, 0, 0), n, "wire");
    ExplicitModel model(mesh);
    model.add_beams("wire", kWireSteel, {beam::Section::circular(d)});
    const int tip = mesh.node_set("end")[0];
    if (tip_mass > 0) model.add_point_mass("tip mass", tip, tip_mass);
    model.fix(mesh.node_set("start"), Dofs::all());
    // A smooth (half-sine) velocity pulse shape is not needed: a short ramped load then release.
    const double t_load = 0.25 * T_guess;
    model.add_nodal_force({tip}, Vec3(0, 1e-4, 0), Curve({{0, 0}, {0.5 * t_load, 1}, {t_load, 0}}));
    ExplicitOptions o = quiet(t_load + periods * T_guess);
    o.history_nodes = {{"tip", tip}};
    ExplicitSolver solver(model, o);
    BeamRun r;
    r.summary = solver.run();
    std::vector<double> t, y;
    const auto& h = solver.history();
    for (std::size_t i = 0; i < h.time.size(); ++i)
        if (h.time[i] > t_load) {
            t.push_back(h.time[i]);
            y.push_back(h.nodes[0].displacement[i].y() - 0.0);
        }
    // Remove the mean (the free vibration is about zero; the mean guards against a small offset).
    double mean = 0;
    for (double v : y) mean += v;
    mean /= y.size();
    for (double& v : y) v -= mean;
    const auto up = upward_crossings(t, y);
    if (up.size() >= 2) r.omega = 2 * kPi * (up.size() - 1) / (up.back() - up.front());
    return r;
}
}  // namespace

// Euler-Bernoulli cantilever: omega1 = 1.8751^2 sqrt(EI / (rho A L^4)). Tolerance 1 %: ten
// lumped-mass elements with cubic bending (discretization error ~0.1 %), and the scaled rotary
// inertia (absent from Euler-Bernoulli theory) adds ~0.1 %.
TEST(BeamCantilever, FirstFrequencyMatchesEulerBernoulli) {
    const double L = 0.4, d = 2e-3;
    const auto s = beam::Section::circular(d);
    const double w1 = 1.875104068711961 * 1.875104068711961 *
                      std::sqrt(kWireSteel.youngs_modulus * s.iz / (kWireSteel.density * s.area * L * L * L * L));
    const auto r = cantilever(L, d, 10, 0.0, 2.2, 2 * kPi / w1);
    std::printf("beam cantilever: omega1 %.5f rad/s vs Euler-Bernoulli %.5f (%.3f %%); energy error %.2e\n", r.omega,
                w1, 100 * (r.omega / w1 - 1), r.summary.energy.relative_error());
    EXPECT_NEAR(r.omega, w1, 0.01 * w1);
    EXPECT_LT(r.summary.energy.relative_error(), 1e-3);
}

// With a tip mass equal to the beam mass (point mass element): the exact frequency equation.
// Tolerance 1 % as above.
TEST(BeamCantilever, TipMassFrequencyMatchesExactFrequencyEquation) {
    const double L = 0.4, d = 2e-3;
    const auto s = beam::Section::circular(d);
    const double m = kWireSteel.density * s.area * L;
    const double lam = tip_mass_lambda(1.0);
    const double w1 = lam * lam * std::sqrt(kWireSteel.youngs_modulus * s.iz / (kWireSteel.density * s.area * L * L * L * L));
    const auto r = cantilever(L, d, 10, m, 2.2, 2 * kPi / w1);
    std::printf("beam + tip mass: omega1 %.5f rad/s vs exact %.5f (lambda %.5f) (%.3f %%)\n", r.omega, w1, lam,
                100 * (r.omega / w1 - 1));
    EXPECT_NEAR(r.omega, w1, 0.01 * w1);
}

// A free wire spinning about an axis normal to it through its centre, two revolutions: the
// corotational beam stores only the centrifugal stretch energy, IE/KE ~ rho omega^2 L^2 / E ~ 1e-8
// (a beam with linear kinematics would store energy of the order of KE). Tolerance 1e-5.
TEST(BeamRotation, FreeSpinCreatesNoStrainEnergy) {
    const double L = 0.2;
    Mesh mesh = line_beam2(Vec3(-L / 2, 0, 0), Vec3(L / 2, 0, 0), 20, "wire");
    ExplicitModel model(mesh);
    model.add_beams("wire", kWireSteel, {beam::Section::circular(1e-3)});
    const Vec3 w(0, 0.6, 0.8);  // |w| = 1 rad/s... scaled below
    const Vec3 omega = 20.0 * w;
    model.set_initial_velocity([&](const Vec3& X) { return Vec3(omega.cross(X)); });
    std::vector<int> all(mesh.node_count());
    for (int i = 0; i < mesh.node_count(); ++i) all[i] = i;
    model.set_initial_angular_velocity(all, omega);
    const double t_end = 2 * 2 * kPi / omega.norm() * 0.25;  // half a revolution (keeps the test short)
    const auto spin = test::run_rigid_spin(model, mesh, omega, t_end);
    const double max_ratio = spin.max_internal_over_kinetic, err = spin.position_error;
    const auto& sum = spin.summary;
    std::printf("beam spin: max IE/KE %.3e, position error %.3e m, energy error %.2e\n", max_ratio, err,
                sum.energy.relative_error());
    EXPECT_LT(max_ratio, 1e-5);
    EXPECT_LT(err, 1e-4 * L);
}

TEST(PointMass, BadInputIsRefusedWithTheCulpritNamed) {
    Mesh mesh = line_beam2(Vec3::Zero(), Vec3(1, 0, 0), 2, "wire");
    ExplicitModel model(mesh);
    try {
        model.add_point_mass("tip", 7, 1.0);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("node 7"), std::string::npos) << e.what();
    }
    model.add_point_mass("tip", 2, -1.0);
    model.add_beams("wire", kWireSteel, {beam::Section::circular(1e-3)});
    EXPECT_THROW(ExplicitSolver(model, quiet(1.0)), InputError);
}
