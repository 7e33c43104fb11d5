// Verification of the Belytschko-Tsay shell against closed forms, on the explicit solver:
//  * static bending by dynamic relaxation (mass damping at the critical value of the first mode,
//    load ramped over half a period): a cantilever strip under a tip load against beam theory, and
//    a clamped and a simply supported square plate under uniform pressure and a clamped one under a
//    central point load against Timoshenko's plate solutions, each on a sequence of meshes
//    (convergence shown);
//  * free vibration: a cantilever plate's first frequencies from explicit runs started in a mode
//    against the linearized model's eigenvalues, the library's MITC4 modal solution (lib/modal) on
//    the same mesh, and the closed-form beam/strip values;
//  * the hourglass energy as a fraction of the internal energy in these bending problems;
//  * triangles (degenerate quadrilaterals) on the cantilever.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>

#include "assembly/model.hpp"
#include "core/eigen_instances.hpp"
#include "explicit_test_support.hpp"
#include "modal/modal.hpp"
#include "shell_test_support.hpp"

using namespace fem;
using namespace fem::test;
using fem::test::quiet;

namespace {

struct Relaxed {
    double w = 0.0;              // the measured displacement at the end
    double ke_over_ie = 0.0;     // kinetic / internal energy at the end (convergence of the relaxation)
    double max_hg_over_ie = 0.0; // largest hourglass / internal energy over the run (after the ramp)
    long steps = 0;
};

// Static solution by dynamic relaxation: mass damping alpha = 2 omega1 (critical for the first
// mode), the load ramped over half a period of it and held; run to ramp + 14 / omega1 (the first
// mode has decayed by e^-14 ~ 1e-6). measure(solver) gives the displacement of interest.
Relaxed relax(ExplicitModel& model, double omega1, const std::function<double(const ExplicitSolver&)>& measure) {
    const double ramp = kPi / omega1;
    model.set_mass_damping(2.0 * omega1);
    ExplicitOptions o = quiet(ramp + 14.0 / omega1);
    o.history_interval = o.end_time / 200;
    ExplicitSolver solver(model, o);
    Relaxed r;
    solver.observer = [&](const ExplicitSolver& s) {
        const auto& h = s.history();
        if (h.time.back() > ramp && h.internal.back() > 0)
            r.max_hg_over_ie = std::max(r.max_hg_over_ie, h.hourglass.back() / h.internal.back());
    };
    const RunSummary sum = solver.run();
    r.w = measure(solver);
    r.ke_over_ie = sum.energy.kinetic / sum.energy.internal;
    r.steps = sum.steps;
    return r;
}

Curve ramp_curve(double omega1) { return Curve({{0.0, 0.0}, {kPi / omega1, 1.0}}); }
}  // namespace

// Cantilever strip L x b x t = 100 x 10 x 1 mm, nu = 0 (so that beam theory holds exactly: no
// anticlastic curvature and no clamping effect at the root), tip load P = 0.01 N spread over the tip
// nodes (deflection 0.02 t: linear). Beam theory with shear: w = P L^3 / (3 E I) + P L / (kappa G b
// t). nx = 4, 8, 16 elements along, 2 across: the error must fall with the mesh (one-point
// elements converge as h^2: measured -1.564, -0.391, -0.098 %, and -0.025 % at nx = 32) and be below
// 0.2 % on the finest.
TEST(ShellBtStatics, CantileverStripMatchesBeamTheory) {
    const ElasticMaterial mat = ElasticMaterial::make("steel nu=0", 210e9, 0.0, 7700);
    const double L = 0.1, b = 0.01, t = 1e-3, P = 0.01;
    const double I = b * t * t * t / 12;
    const double w_beam = P * L * L * L / (3 * mat.youngs_modulus * I) + P * L / (5.0 / 6.0 * mat.shear_modulus() * b * t);
    const double omega1 = 1.8751 * 1.8751 * std::sqrt(mat.youngs_modulus * I / (mat.density * b * t * L * L * L * L));
    double previous = 1e300;
    for (int nx : {4, 8, 16}) {
        const int ny = 2;
        Mesh mesh = rectangle_quads(L, b, nx, ny, ElementShape::Quad4, "strip");
        ExplicitModel model(mesh);
        model.add_shells("strip", mat, {.thickness = t});
        model.fix(mesh.node_set("x0"), Dofs::all());
        // Consistent nodal loads of a uniform line load along the tip edge: half at the corners.
        for (int node : mesh.node_set("x1")) {
            const double y = mesh.nodes[node].y();
            const double share = (y < 1e-12 || y > b - 1e-12) ? 0.5 / ny : 1.0 / ny;
            model.add_nodal_force({node}, Vec3(0, 0, P * share), ramp_curve(omega1));
        }
        const auto tip = mesh.node_set("x1");
        const Relaxed r = relax(model, omega1, [&](const ExplicitSolver& s) {
            double w = 0;
            for (int node : tip) w += s.state().x[node].z() / tip.size();
            return w;
        });
        const double err = r.w / w_beam - 1;
        std::printf("cantilever nx %2d: w %.6e m (beam %.6e), error %+.3f %%, KE/IE %.1e, max HG/IE %.1e, %ld steps\n",
                    nx, r.w, w_beam, 100 * err, r.ke_over_ie, r.max_hg_over_ie, r.steps);
        EXPECT_LT(r.ke_over_ie, 1e-6);
        EXPECT_LT(std::abs(err), previous);
        previous = std::abs(err);
        if (nx == 16) {
            EXPECT_LT(std::abs(err), 2e-3);
        }
        EXPECT_LT(r.max_hg_over_ie, 1e-3);  // uniform bending excites no hourglass mode
    }
}

namespace {
enum class Support { Clamped, SimplySupported };
enum class Load { Uniform, CentralPoint };

// A square plate a x a x t (a/t = 100, nu = 0.3: Timoshenko's tables), quarter model [0, a/2]^2 with
// symmetry along x = a/2 and y = a/2 (normal translation and the two rotations about in-plane
// axes normal to the line... i.e. ux, ry, rz on x = a/2; uy, rx, rz on y = a/2), n x n elements.
// Clamped edges: every DOF. Simply supported ("hard", the Kirchhoff support): w and the rotation
// about the edge's in-plane normal (which would tilt the edge line) held; the edges free to move
// in the plane as in Timoshenko's solution (held in-plane, the membrane action would stiffen the
// plate by ~(w/t)^2: measured -0.14 % at w = 0.02 t).
// Returns the centre deflection by dynamic relaxation.
Relaxed square_plate(Support support, Load load, int n, double q_or_P, const ElasticMaterial& mat, double a, double t) {
    Mesh mesh = rectangle_quads(a / 2, a / 2, n, n, ElementShape::Quad4, "plate");
    ExplicitModel model(mesh);
    model.add_shells("plate", mat, {.thickness = t});
    model.fix(mesh.node_set("x1"), Dofs::of(Dofs::x | Dofs::ry | Dofs::rz));
    model.fix(mesh.node_set("y1"), Dofs::of(Dofs::y | Dofs::rx | Dofs::rz));
    if (support == Support::Clamped) {
        model.fix(mesh.node_set("x0"), Dofs::all());
        model.fix(mesh.node_set("y0"), Dofs::all());
    } else {
        model.fix(mesh.node_set("x0"), Dofs::of(Dofs::z | Dofs::rx));
        model.fix(mesh.node_set("y0"), Dofs::of(Dofs::z | Dofs::ry));
    }
    const double D = mat.youngs_modulus * t * t * t / (12 * (1 - mat.poissons_ratio * mat.poissons_ratio));
    const double omega1 =
        (support == Support::Clamped ? 35.99 : 2 * kPi * kPi) * std::sqrt(D / (mat.density * t)) / (a * a);
    int centre = -1;
    for (int i = 0; i < mesh.node_count(); ++i)
        if ((mesh.nodes[i] - Vec3(a / 2, a / 2, 0)).norm() < 1e-9 * a) centre = i;
    if (load == Load::CentralPoint) {
        model.add_nodal_force({centre}, Vec3(0, 0, q_or_P / 4), ramp_curve(omega1));  // a quarter of P
    } else {
        const double h = a / 2 / n;
        for (int i = 0; i < mesh.node_count(); ++i) {
            const Vec3& X = mesh.nodes[i];
            const bool ex = X.x() < 1e-9 * a || X.x() > a / 2 - 1e-9 * a, ey = X.y() < 1e-9 * a || X.y() > a / 2 - 1e-9 * a;
            const double area = h * h * (ex ? 0.5 : 1.0) * (ey ? 0.5 : 1.0);  // tributary area
            model.add_nodal_force({i}, Vec3(0, 0, q_or_P * area), ramp_curve(omega1));
        }
    }
    return relax(model, omega1, [&](const ExplicitSolver& s) { return s.state().x[centre].z(); });
}
}  // namespace

// Timoshenko and Woinowsky-Krieger (Theory of plates and shells, Tables 8, 35 and 55; nu = 0.3):
// centre deflection of a square plate, w = alpha q a^4 / D under uniform pressure q (simply
// supported alpha = 0.00406, clamped 0.00126) and w = alpha P a^2 / D under a central force P
// (clamped, alpha = 0.00560). The more precise series values 0.0040624 and 0.0012653 are used for
// the uniform cases. Meshes of 4, 8, 16 elements per half side. Uniform loads: the error falls with
// the mesh and is within 0.5 % on the finest. The element is a Mindlin plate, whose deflection is
// slightly above Kirchhoff's (transverse shear): for the simply supported plate exactly by M / (kappa
// G t) (M the Marcus moment, +0.052 % here), for the clamped one by about +0.19 % at a/t = 100
// (+19 % at a/t = 10); the measured errors (+0.063 % and +0.228 % at n = 16, h^2-extrapolated
// +0.04 % and +0.20 %) converge to these, not to zero. Point load: within 1 % on
// 8 and 16; no monotone convergence is expected, a Mindlin plate's deflection under a point force
// is singular, P / (2 pi kappa G t) ln(a / h) (+0.28 % of w at n = 16, growing with refinement).
// The hourglass energy stays below 1 % of the internal energy even under the point load (the
// transverse hourglass mode is what a point load on one-point elements excites).
TEST(ShellBtStatics, SquarePlatesMatchTimoshenko) {
    const ElasticMaterial mat = ElasticMaterial::make("steel nu=0.3", 210e9, 0.3, 7700);
    const double a = 0.2, t = 2e-3, q = 1000.0, P = 10.0;
    const double D = mat.youngs_modulus * t * t * t / (12 * (1 - 0.09));
    struct Case {
        const char* name;
        Support support;
        Load load;
        double w_exact;
    };
    const Case cases[] = {
        {"simply supported, uniform", Support::SimplySupported, Load::Uniform, 0.0040624 * q * a * a * a * a / D},
        {"clamped, uniform", Support::Clamped, Load::Uniform, 0.0012653 * q * a * a * a * a / D},
        {"clamped, central force", Support::Clamped, Load::CentralPoint, 0.00560 * P * a * a / D},
    };
    for (const auto& cs : cases) {
        double previous = 1e300;
        for (int n : {4, 8, 16}) {
            const Relaxed r = square_plate(cs.support, cs.load, n, cs.load == Load::Uniform ? q : P, mat, a, t);
            const double err = r.w / cs.w_exact - 1;
            std::printf("%-26s n %2d: w %.6e m (Timoshenko %.6e), error %+.3f %%, KE/IE %.1e, max HG/IE %.2e, %ld "
                        "steps\n",
                        cs.name, n, r.w, cs.w_exact, 100 * err, r.ke_over_ie, r.max_hg_over_ie, r.steps);
            EXPECT_LT(r.ke_over_ie, 1e-6) << cs.name;
            if (cs.load == Load::Uniform) {
                EXPECT_LT(std::abs(err), previous) << cs.name << " n " << n;
                if (n == 16) {
                    EXPECT_LT(std::abs(err), 0.005) << cs.name;
                }
            } else if (n >= 8) {
                EXPECT_LT(std::abs(err), 0.01) << cs.name << " n " << n;
            }
            previous = std::abs(err);
            EXPECT_LT(r.max_hg_over_ie, 0.01) << cs.name << " n " << n;
        }
    }
}

namespace {
// Out-of-plane modes (kinetic energy mostly in w) of a dense eigensolution, ascending: frequencies
// [rad/s] and shapes (6 DOFs per node, zero on fixed DOFs).
struct Modes {
    std::vector<double> omega;
    std::vector<Eigen::VectorXd> shape;
};
Modes out_of_plane_modes(const test::DenseShellSystem& s, const std::vector<bool>& fixed, int count) {
    std::vector<int> free;
    for (int i = 0; i < static_cast<int>(fixed.size()); ++i)
        if (!fixed[i]) free.push_back(i);
    const int n = static_cast<int>(free.size());
    Eigen::MatrixXd A(n, n);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
            A(a, b) = 0.5 * (s.K(free[a], free[b]) + s.K(free[b], free[a])) / std::sqrt(s.mass[free[a]] * s.mass[free[b]]);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
    Modes m;
    for (int k = 0; k < n && static_cast<int>(m.omega.size()) < count; ++k) {
        Eigen::VectorXd phi = Eigen::VectorXd::Zero(fixed.size());
        for (int a = 0; a < n; ++a) phi[free[a]] = eig.eigenvectors()(a, k) / std::sqrt(s.mass[free[a]]);
        double ew = 0, etot = 0;  // kinetic energy shares
        for (int i = 0; i < phi.size(); ++i) {
            etot += s.mass[i] * phi[i] * phi[i];
            if (i % 6 == 2) ew += s.mass[i] * phi[i] * phi[i];
        }
        if (ew > 0.5 * etot && eig.eigenvalues()[k] > 0) {
            m.omega.push_back(std::sqrt(eig.eigenvalues()[k]));
            m.shape.push_back(phi);
        }
    }
    return m;
}

// Frequency of a free vibration started with velocity = mode shape (small amplitude): the modal
// coordinate q(t) = sum_i m_i phi_i u_i over the translations, its upward zero crossings (linear
// interpolation) over `periods` periods.
double explicit_frequency(const Mesh& mesh, const ElasticMaterial& mat, const ShellOptions& sec,
                          const std::vector<int>& clamped, const Eigen::VectorXd& phi, double omega_guess,
                          double periods) {
    ExplicitModel model(mesh);
    model.add_shells(mesh.blocks[0].part, mat, sec);
    model.fix(clamped, Dofs::all());
    const double scale = 1e-3 / phi.cwiseAbs().maxCoeff();  // 1 mm/s peak
    std::vector<Vec3> v(mesh.node_count());
    for (int i = 0; i < mesh.node_count(); ++i) {
        v[i] = scale * phi.segment<3>(6 * i);
        model.set_initial_angular_velocity({i}, scale * phi.segment<3>(6 * i + 3));
    }
    model.set_initial_velocity([&](const Vec3& X) {
        for (int i = 0; i < mesh.node_count(); ++i)
            if (mesh.nodes[i] == X) return v[i];
        return Vec3(Vec3::Zero());
    });
    ExplicitSolver solver(model, quiet(periods * 2 * kPi / omega_guess));
    std::vector<double> t, q;
    solver.observer = [&](const ExplicitSolver& s) {
        double sum = 0;
        for (int i = 0; i < mesh.node_count(); ++i)
            sum += s.state().mass[i] * phi.segment<3>(6 * i).dot(s.state().x[i] - s.state().X[i]);
        t.push_back(s.time());
        q.push_back(sum);
    };
    solver.run();
    const std::vector<double> up = upward_crossings(t, q);
    if (up.size() < 2) return 0.0;
    return 2 * kPi * (up.size() - 1) / (up.back() - up.front());
}
}  // namespace

// Free vibration of a cantilever plate 100 x 20 x 2 mm (steel, nu = 0.28), 20 x 4 elements:
//  * explicit runs started in each of the first three out-of-plane modes of the linearized BT model
//    (first bending, second bending, first torsion) oscillate at its eigenfrequencies (0.1 %: the
//    central-difference period error (omega dt)^2 / 24 is ~1e-6; the rest is the zero-crossing
//    timing and the small amplitude's nonlinearity);
//  * against MITC4 (lib/assembly + lib/modal, lumped mass, the same mesh): bending within 1 %
//    (measured -0.3 %, -0.9 %); torsion 6.9 % lower. Most of that is the scaled rotary inertia of
//    the explicit model (shellbt::rotational_inertia, J = 0.129 m a^2 per node instead of the
//    physical m t^2 / 12): the five nodes across the width add 0.645 rho t a^3 per unit length to
//    the strip's polar inertia rho t b^3 / 12, +12 % with four elements across, -5.5 % in
//    frequency; it falls as (a/b)^2 with the mesh across the width. With the physical rotary
//    inertia the same BT stiffness is 1.4 % below MITC4 in torsion (the one-point element's
//    torsional stiffness) and within 0.3 % in bending;
//  * against the closed forms (Euler-Bernoulli beam with E; St-Venant torsion of a thin strip with
//    J = b t^3 (1/3 - 0.21 t/b (1 - (t/b)^4/12)), Roark): bending within 2 % (the clamped root
//    restrains the anticlastic curvature the beam formula ignores), torsion within 2 % for MITC4
//    and the BT stiffness with physical inertia.
TEST(ShellBtDynamics, CantileverPlateFrequenciesMatchMitc4AndClosedForms) {
    const ElasticMaterial mat = ElasticMaterial::make("steel", 210e9, 0.28, 7700);
    const double L = 0.1, b = 0.02, t = 2e-3;
    Mesh mesh = rectangle_quads(L, b, 20, 4, ElementShape::Quad4, "plate");
    const ShellOptions sec{.thickness = t};
    const auto& clamped = mesh.node_set("x0");

    // BT, linearized, with the explicit model's lumped masses (and with the physical rotary inertia).
    ShellGroup g(mesh, 0, mat, sec);
    auto sys = test::dense_shell_system(mesh, g);
    std::vector<bool> fixed(sys.mass.size(), false);
    for (int node : clamped)
        for (int d = 0; d < 6; ++d) fixed[6 * node + d] = true;
    const Modes bt = out_of_plane_modes(sys, fixed, 3);
    auto physical = sys;
    for (int e = 0; e < g.size(); ++e)
        for (int I = 0; I < 4; ++I)
            for (int d = 3; d < 6; ++d) physical.mass[6 * g.connectivity(e)[I] + d] = 0.0;
    for (int e = 0; e < g.size(); ++e)
        for (int I = 0; I < 4; ++I)
            for (int d = 3; d < 6; ++d)
                physical.mass[6 * g.connectivity(e)[I] + d] += g.lumped_mass(e).mass[I] * t * t / 12;
    const Modes bt_phys = out_of_plane_modes(physical, fixed, 3);

    // MITC4 on the same mesh, lumped mass.
    Model model(mesh);
    model.add_shell_part("plate", t, mat, solid::MassKind::Lumped);
    model.fix_node_set("x0");
    const auto sysm = model.assemble();
    const auto mitc = modal::solve_modes(sysm, {.modes = 12});
    std::vector<double> mitc_w;  // out-of-plane ones: uz dominates the translations
    for (int k = 0; k < mitc.frequencies_hz.size() && mitc_w.size() < 3; ++k) {
        const auto u = sysm.translations(mitc.shapes.col(k));
        double uz = 0, uxy = 0;
        for (std::size_t i = 0; i < u.size(); i += 3) {
            uz += u[i + 2] * u[i + 2];
            uxy += u[i] * u[i] + u[i + 1] * u[i + 1];
        }
        if (uz > uxy) mitc_w.push_back(2 * kPi * mitc.frequencies_hz[k]);
    }
    ASSERT_EQ(mitc_w.size(), 3u);

    // Closed forms.
    const double E = mat.youngs_modulus, G = mat.shear_modulus(), rho = mat.density, A = b * t, I = b * t * t * t / 12;
    const double eb = std::sqrt(E * I / (rho * A * L * L * L * L));
    const double J = b * t * t * t * (1.0 / 3 - 0.21 * t / b * (1 - std::pow(t / b, 4) / 12));
    const double closed[3] = {1.875104 * 1.875104 * eb, 4.694091 * 4.694091 * eb,
                              kPi / (2 * L) * std::sqrt(G * J / (rho * (b * b * b * t + b * t * t * t) / 12))};
    const char* names[3] = {"1st bending", "2nd bending", "1st torsion"};

    for (int k = 0; k < 3; ++k) {
        const double w_explicit =
            explicit_frequency(mesh, mat, sec, clamped, bt.shape[k], bt.omega[k], k == 0 ? 3.0 : 6.0);
        std::printf("%-12s BT explicit %9.2f rad/s, BT linear %9.2f, BT physical rotary inertia %9.2f, MITC4 %9.2f, "
                    "closed form %9.2f\n",
                    names[k], w_explicit, bt.omega[k], bt_phys.omega[k], mitc_w[k], closed[k]);
        EXPECT_NEAR(w_explicit, bt.omega[k], 1e-3 * bt.omega[k]) << names[k];
        if (k < 2) {
            EXPECT_NEAR(bt.omega[k], mitc_w[k], 0.01 * mitc_w[k]) << names[k];
            EXPECT_NEAR(bt_phys.omega[k], mitc_w[k], 0.01 * mitc_w[k]) << names[k];
            EXPECT_NEAR(bt.omega[k], closed[k], 0.02 * closed[k]) << names[k];
        } else {
            // Torsion: the scaled inertia's share (BT physical vs BT) is the expected ~5.5 %.
            EXPECT_NEAR(bt.omega[k] / bt_phys.omega[k], 1 / std::sqrt(1.12), 0.01) << names[k];
            EXPECT_NEAR(bt_phys.omega[k], mitc_w[k], 0.02 * mitc_w[k]) << names[k];
            EXPECT_NEAR(bt_phys.omega[k], closed[k], 0.02 * closed[k]) << names[k];
            EXPECT_NEAR(mitc_w[k], closed[k], 0.02 * closed[k]) << names[k];
        }
    }
}


// Triangles on the cantilever strip of CantileverStripMatchesBeamTheory, one element across and
// each quad split in two. As plain degenerate quadrilaterals (one-point shear) they locked: -93 %
// (nx = 8), -75 % (16), -45 % (32); with the edge-based shear (shell_bt_explicit.hpp): -0.39 %,
// -0.095 %, -0.021 % (ny = 2), converging as h^2 like the quadrilaterals. Required: the error falls
// with the mesh, below 0.5 % at nx = 8 and 0.2 % at nx = 16.
TEST(ShellBtStatics, TriangleCantileverAgainstBeamTheory) {
    const ElasticMaterial mat = ElasticMaterial::make("steel nu=0", 210e9, 0.0, 7700);
    const double L = 0.1, b = 0.01, t = 1e-3, P = 0.01;
    const double I = b * t * t * t / 12;
    const double w_beam = P * L * L * L / (3 * mat.youngs_modulus * I) + P * L / (5.0 / 6.0 * mat.shear_modulus() * b * t);
    const double omega1 = 1.8751 * 1.8751 * std::sqrt(mat.youngs_modulus * I / (mat.density * b * t * L * L * L * L));
    double previous = 1e300;
    for (int nx : {8, 16}) {
        const int ny = 1;
        Mesh mesh = test::split_into_triangles(rectangle_quads(L, b, nx, ny, ElementShape::Quad4, "strip"));
        ExplicitModel model(mesh);
        model.add_shells("strip", mat, {.thickness = t});
        model.fix(mesh.node_set("x0"), Dofs::all());
        for (int node : mesh.node_set("x1")) {
            const double y = mesh.nodes[node].y();
            const double share = (y < 1e-12 || y > b - 1e-12) ? 0.5 / ny : 1.0 / ny;
            model.add_nodal_force({node}, Vec3(0, 0, P * share), ramp_curve(omega1));
        }
        const auto tip = mesh.node_set("x1");
        const Relaxed r = relax(model, omega1, [&](const ExplicitSolver& s) {
            double w = 0;
            for (int node : tip) w += s.state().x[node].z() / tip.size();
            return w;
        });
        const double err = r.w / w_beam - 1;
        std::printf("triangles nx %2d: w %.6e m (beam %.6e), error %+.3f %%, KE/IE %.1e, %ld steps\n", nx, r.w, w_beam,
                    100 * err, r.ke_over_ie, r.steps);
        EXPECT_LT(r.ke_over_ie, 1e-6);
        EXPECT_LT(std::abs(err), previous);
        EXPECT_LT(std::abs(err), nx == 8 ? 5e-3 : 2e-3);
        previous = std::abs(err);
    }
}
