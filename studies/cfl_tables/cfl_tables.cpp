// Study cfl_tables: the critical time step of explicit integration.
//
// Reproduces thesis Sec 2.3.2-2.3.5:
//   Eq 2-24..2-26  the lumped 1D rod element: omega_max = 2 c_w / L_e, dt_crit = L_e / c_w
//   Table 2-1      critical-time-step formulas per element type, evaluated on real node coordinates
//   Table 2-2      element size and shape (triangle, Quad 1, Quad 2 of Fig 2-5): L_e, c_w, dt, steps
//   Table 2-3      parameter ranges of Fig 2-6: dt versus E, rho, L_e and nu for the quad shell
//   Sec 2.3.5      observations 1-4, as trend checks
//
// Run:  make cfl_tables        (or build/studies/cfl_tables --figures figures)
// Out:  build/results/cfl_tables/{checks.json, runs.json, *.dat}, figures/{fig-2-5,fig-2-6,eq-2-25}.svg,
//       figures/table-2-1.md, figures/table-2-2.md
//
// Everything below goes through the library function the explicit solver calls every cycle,
// fem::cfl::critical_time_step(shape, nodes, material, strain rate), so this study also documents it.
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <sstream>
#include <vector>

#include <Eigen/Eigenvalues>

#include "check/study.hpp"
#include "core/eigen_instances.hpp"
#include "core/units.hpp"
#include "element/critical_time_step.hpp"
#include "io/atomic_file.hpp"
#include "io/table.hpp"
#include "material/elastic.hpp"

using namespace fem;
using units::GPa;
using units::mm;
using units::us;

namespace {

// A flat rectangle a x b in the x-y plane, counter-clockwise: the Quad shells of Fig 2-5.
std::array<Vec3, 4> rectangle(double a, double b) {
    return {Vec3(0, 0, 0), Vec3(a, 0, 0), Vec3(a, b, 0), Vec3(0, b, 0)};
}

// A hexahedron whose top face is shifted by `shear` in x: a parallelepiped (shear = 0: a cube).
std::array<Vec3, 8> sheared_hexahedron(double a, double shear) {
    std::array<Vec3, 8> x;
    const auto bottom = rectangle(a, a);
    for (int i = 0; i < 4; ++i) {
        x[i] = bottom[i];
        x[i + 4] = bottom[i] + Vec3(shear, 0, a);
    }
    return x;
}

std::array<Vec3, 4> regular_tetrahedron(double a) {
    return {Vec3(0, 0, 0), Vec3(a, 0, 0), Vec3(a / 2, a * std::sqrt(3.0) / 2, 0),
            Vec3(a / 2, a * std::sqrt(3.0) / 6, a * std::sqrt(2.0 / 3.0))};
}

std::vector<double> linspace(double a, double b, int n) {
    std::vector<double> v(n);
    for (int i = 0; i < n; ++i) v[i] = a + (b - a) * i / (n - 1);
    return v;
}

}  // namespace

int main(int argc, char** argv) {
    return check::run_study("cfl_tables", argc, argv, [](check::Study& study) {
        const auto& out = study.results_dir();

        // The material of Table 2-2: aluminium AL6061.
        const auto al6061 = ElasticMaterial::make("AL6061", 69 * GPa, 0.33, 2700.0);

        // ------------------------------------------------------------------------------------------
        // Step 1. Eq 2-22..2-26: one rod element of length L_e with stiffness AE/L_e [1 -1; -1 1]
        // (Eq 2-22) and lumped mass rho A L_e / 2 I (Eq 2-23). Solving det(K - w^2 M) = 0 (Eq 2-24)
        // numerically gives the rigid mode w = 0 and the highest mode w_max = 2 c_w / L_e (Eq 2-25),
        // hence the stability limit dt <= 2 / w_max = L_e / c_w (Eq 2-7, Eq 2-26).
        {
            const double L = 10 * mm, A = 1e-4;
            const double E = al6061.youngs_modulus, rho = al6061.density;
            Eigen::Matrix2d K, M;
            K << 1, -1, -1, 1;
            K *= A * E / L;
            M = Eigen::Matrix2d::Identity() * (rho * A * L / 2);
            Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> eig(K, M);
            const double omega_max = std::sqrt(eig.eigenvalues().maxCoeff());
            const double c = bar_wave_speed(al6061);
            study.check("eq-2-25/omega-max-ratio", omega_max / (2 * c / L),
                        fmt::format("omega_max = {:.6g} rad/s for a 10 mm AL6061 rod", omega_max));
            study.check("eq-2-26/dt-ratio", (2 / omega_max) / cfl::time_step(L, c));

            // Figure for Eq 2-25: the highest frequency of an n-element rod, free-free and with
            // one end fixed, with lumped mass (Eq 2-23) and with consistent mass (rho A L / 6
            // [2 1; 1 2]). Lumped free-free is exactly 2 c / L_e for every n; one fixed end
            // approaches it from below; consistent mass gives up to sqrt(3) times more, i.e. a
            // step sqrt(3) smaller -- one reason explicit codes lump the mass.
            Eigen::Matrix2d Mc;
            Mc << 2, 1, 1, 2;
            Mc *= rho * A * L / 6;
            io::Table conv;
            std::vector<double> n_el, lumped_free, lumped_fixed, consistent_free;
            for (int n : {1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64}) {
                Eigen::MatrixXd Kn = Eigen::MatrixXd::Zero(n + 1, n + 1), Mn = Kn, Mcn = Kn;
                for (int e = 0; e < n; ++e) {
                    Kn.block<2, 2>(e, e) += K;
                    Mn.block<2, 2>(e, e) += M;
                    Mcn.block<2, 2>(e, e) += Mc;
                }
                auto omega_max_ratio = [&](const Eigen::MatrixXd& k, const Eigen::MatrixXd& m) {
                    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> en(k, m, Eigen::EigenvaluesOnly);
                    return std::sqrt(en.eigenvalues().maxCoeff()) / (2 * c / L);
                };
                n_el.push_back(n);
                lumped_free.push_back(omega_max_ratio(Kn, Mn));
                consistent_free.push_back(omega_max_ratio(Kn, Mcn));
                // Node 0 fixed: drop its row and column.
                lumped_fixed.push_back(omega_max_ratio(Kn.bottomRightCorner(n, n), Mn.bottomRightCorner(n, n)));
            }
            conv.add("elements", n_el).add("lumped_free_free", lumped_free).add("lumped_fixed_free", lumped_fixed)
                .add("consistent_free_free", consistent_free);
            io::write_dat(out / "eq-2-25.dat", conv);
        }

        // ------------------------------------------------------------------------------------------
        // Step 2. Table 2-1 on sample elements: each row's formula evaluated by the library from node
        // coordinates. Bulk viscosity enters solids only under compression (eps_kk < 0).
        std::ostringstream table21;
        table21 << "| element | geometry | L_e (mm) | c_w (m/s) | eps_kk (1/s) | dt (us) |\n|---|---|---|---|---|---|\n";
        auto row21 = [&](ElementShape shape, const char* geometry, std::span<const Vec3> x, double rate) {
            const double L = cfl::characteristic_length(shape, x);
            const double dt = cfl::critical_time_step(shape, x, al6061, rate);
            table21 << fmt::format("| {} | {} | {:.4f} | {:.1f} | {} | {:.4f} |\n", to_string(shape), geometry,
                                   L / mm, cfl::wave_speed(shape, al6061), rate, dt / us);
            return std::pair{L, dt};
        };
        {
            const std::array<Vec3, 2> beam = {Vec3(0, 0, 0), Vec3(10 * mm, 0, 0)};
            study.check("table-2-1/beam/dt", row21(ElementShape::Beam2, "10 mm", beam, 0).second / us);

            const auto cube = sheared_hexahedron(10 * mm, 0);
            const auto [L_cube, dt_cube] = row21(ElementShape::Hex8, "10 mm cube", cube, 0);
            study.check("table-2-1/hexahedron/cube/L_e", L_cube / mm);
            study.check("table-2-1/hexahedron/cube/dt", dt_cube / us);
            study.check("table-2-1/hexahedron/cube-compressed/dt",
                        row21(ElementShape::Hex8, "10 mm cube", cube, -1000).second / us,
                        "bulk viscosity lowers the step of a compressing element");

            const auto sheared = sheared_hexahedron(10 * mm, 5 * mm);
            study.check("table-2-1/hexahedron/sheared/L_e",
                        row21(ElementShape::Hex8, "10 mm, top shifted 5 mm", sheared, 0).first / mm);

            const auto tet = regular_tetrahedron(10 * mm);
            study.check("table-2-1/tetrahedron/regular/L_e",
                        row21(ElementShape::Tet4, "regular, 10 mm edges", tet, 0).first / mm);
            study.check("table-2-1/tetrahedron/regular-compressed/dt",
                        row21(ElementShape::Tet4, "regular, 10 mm edges", tet, -1000).second / us);
        }

        // ------------------------------------------------------------------------------------------
        // Step 3. Table 2-2 / Fig 2-5: the triangle (legs L1 = L2 = 10 mm), Quad 1 (10 x 10 mm) and
        // Quad 2 (10 x 5 mm) in AL6061, and the number of steps a 1 ms problem takes with each.
        struct ShellCase { const char* id; const char* label; ElementShape shape; std::vector<Vec3> nodes; double L1, L2; };
        const auto quad1 = rectangle(10 * mm, 10 * mm), quad2 = rectangle(10 * mm, 5 * mm);
        const std::vector<ShellCase> shells = {
            {"triangle", "Triangular", ElementShape::Tri3, {Vec3(0, 0, 0), Vec3(10 * mm, 0, 0), Vec3(0, 10 * mm, 0)}, 0.01, 0.01},
            {"quad-1", "Quad 1", ElementShape::Quad4, {quad1.begin(), quad1.end()}, 0.01, 0.01},
            {"quad-2", "Quad 2", ElementShape::Quad4, {quad2.begin(), quad2.end()}, 0.01, 0.005},
        };
        const double duration = 1 * units::ms;
        std::ostringstream table22;
        table22 << "| Shell element | L1, L2 (m) | L_e (m) | c_w (m/s) | dt (us) | steps to 1 ms | thesis steps |\n"
                   "|---|---|---|---|---|---|---|\n";
        const std::array<int, 3> thesis_steps = {758, 535, 1070};
        std::array<double, 3> steps{};
        io::Table fig25;
        std::vector<double> fx, fy, fid;
        for (std::size_t k = 0; k < shells.size(); ++k) {
            const auto& s = shells[k];
            const double L = cfl::characteristic_length(s.shape, s.nodes);
            const double c = cfl::wave_speed(s.shape, al6061);
            const double dt = cfl::critical_time_step(s.shape, s.nodes, al6061);
            steps[k] = duration / dt;
            const std::string id = std::string("table-2-2/") + s.id;
            study.check(id + "/L_e", L);
            study.check(id + "/dt", dt / us);
            study.check(id + "/steps-1ms", steps[k]);
            if (k == 0) study.check("table-2-2/c_w", c);
            table22 << fmt::format("| {} | {}, {} | {:.6f} | {:.2f} | {:.4f} | {:.2f} | {} |\n", s.label, s.L1, s.L2, L,
                                   c, dt / us, steps[k], thesis_steps[k]);
            for (std::size_t n = 0; n <= s.nodes.size(); ++n) {  // closed outline for the drawing
                const Vec3& p = s.nodes[n % s.nodes.size()];
                fx.push_back(p.x() / mm + 15.0 * k);
                fy.push_back(p.y() / mm);
                fid.push_back(k);
            }
        }
        fig25.add("x_mm", fx).add("y_mm", fy).add("element", fid);
        io::write_dat(out / "fig-2-5.dat", fig25);
        study.check("table-2-2/ratio-quad-2-to-quad-1", steps[2] / steps[1]);
        study.check("table-2-2/ratio-triangle-to-quad-1", steps[0] / steps[1]);

        // ------------------------------------------------------------------------------------------
        // Step 4. Table 2-3 / Fig 2-6: one parameter varied at a time over the thesis's ranges, the
        // others held at E 70 GPa, rho 2700 kg/m3, L_e 10 mm, nu 0.3. The quad is a square of side
        // L_e, so that A / max side = L_e.
        struct Base { double E = 70 * GPa, rho = 2700, L = 10 * mm, nu = 0.3; };
        auto quad_dt = [](const Base& p) {
            const auto m = ElasticMaterial::make("Table 2-3", p.E, p.nu, p.rho);
            const auto x = rectangle(p.L, p.L);
            return cfl::critical_time_step(ElementShape::Quad4, x, m) / us;
        };
        struct Curve { const char* name; std::vector<double> values, dt; };
        Curve E_curve{"E_GPa", linspace(10, 500, 50)}, rho_curve{"rho", linspace(100, 5000, 50)},
            L_curve{"L_mm", linspace(1, 25, 49)}, nu_curve{"nu", linspace(0, 0.49, 50)};
        for (double v : E_curve.values) E_curve.dt.push_back(quad_dt({.E = v * GPa}));
        for (double v : rho_curve.values) rho_curve.dt.push_back(quad_dt({.rho = v}));
        for (double v : L_curve.values) L_curve.dt.push_back(quad_dt({.L = v * mm}));
        for (double v : nu_curve.values) nu_curve.dt.push_back(quad_dt({.nu = v}));
        for (const Curve* c : {&E_curve, &rho_curve, &L_curve, &nu_curve}) {
            io::Table t;
            t.add(c->name, c->values).add("dt_us", c->dt);
            io::write_dat(out / (std::string("fig-2-6-") + c->name + ".dat"), t);
        }
        auto ends = [](const Curve& c) { return std::vector<double>{c.dt.front(), c.dt.back()}; };
        study.check("table-2-3/E-curve/endpoints", ends(E_curve));
        study.check("table-2-3/rho-curve/endpoints", ends(rho_curve));
        study.check("table-2-3/L-curve/endpoints", ends(L_curve));
        study.check("table-2-3/nu-curve/endpoints", ends(nu_curve));

        // Observation 1: which parameter's range moves dt the least (max/min over the range).
        auto spread = [](const Curve& c) {
            const auto [lo, hi] = std::minmax_element(c.dt.begin(), c.dt.end());
            return *hi / *lo;
        };
        const std::array<std::pair<const char*, double>, 4> spreads = {{{"E", spread(E_curve)},
            {"rho", spread(rho_curve)}, {"L_e", spread(L_curve)}, {"nu", spread(nu_curve)}}};
        const auto least = *std::min_element(spreads.begin(), spreads.end(),
                                             [](auto& a, auto& b) { return a.second < b.second; });
        study.trend("sec-2.3.5/obs-1/least-sensitive", std::string(least.first),
                    fmt::format("dt max/min over the ranges: E {:.2f}, rho {:.2f}, L_e {:.2f}, nu {:.3f}. E and rho "
                                "move dt by the same factor, since dt ~ sqrt(rho / E).",
                                spreads[0].second, spreads[1].second, spreads[2].second, spreads[3].second));
        // Observation 1 (E): the slope |d dt / dE| along the sampled curve is largest at its low end.
        std::size_t steepest = 0;
        double steepest_slope = 0;
        for (std::size_t i = 0; i + 1 < E_curve.dt.size(); ++i) {
            const double slope = std::abs((E_curve.dt[i + 1] - E_curve.dt[i]) / (E_curve.values[i + 1] - E_curve.values[i]));
            if (slope > steepest_slope) steepest_slope = slope, steepest = i;
        }
        study.trend("sec-2.3.5/obs-1/steepest-at-small-E", fmt::format("steepest at E = {:g} GPa", E_curve.values[steepest]));
        auto monotonic = [](const std::vector<double>& v) {
            if (std::is_sorted(v.begin(), v.end(), std::less<>())) return "increases";
            if (std::is_sorted(v.begin(), v.end(), std::greater<>())) return "decreases";
            return "not monotonic";
        };
        study.trend("sec-2.3.5/obs-1/density", monotonic(rho_curve.dt));
        study.trend("sec-2.3.5/obs-3/modulus", monotonic(E_curve.dt));
        // Observation 2: dt / L_e is the same constant along the whole curve.
        double worst = 0;
        for (std::size_t i = 0; i < L_curve.dt.size(); ++i)
            worst = std::max(worst, std::abs(L_curve.dt[i] / L_curve.values[i] / (L_curve.dt[0] / L_curve.values[0]) - 1));
        study.trend_holds("sec-2.3.5/obs-2/length", worst < 1e-12, worst < 1e-12 ? "proportional" : "not proportional",
                    fmt::format("dt / L_e varies by {:.1e} relative along the curve", worst));

        // Observation 4: selective mass scaling. A mesh of 99 Quad 1 elements and one Quad 2 is held
        // to Quad 2's step (Eq 2-27 takes the minimum). Scaling Quad 2's density by (dt_target / dt)^2
        // lifts its step to the target, at the cost of a small added mass.
        {
            const double dt1 = cfl::critical_time_step(ElementShape::Quad4, quad1, al6061);
            const double dt2 = cfl::critical_time_step(ElementShape::Quad4, quad2, al6061);
            const double scale = cfl::density_scale_for_time_step(dt2, dt1);
            const auto scaled = ElasticMaterial::make("AL6061 mass-scaled", al6061.youngs_modulus,
                                                      al6061.poissons_ratio, al6061.density * scale);
            const double dt2_scaled = cfl::critical_time_step(ElementShape::Quad4, quad2, scaled);
            const double global = std::min(dt1, dt2_scaled);
            const double mass_quad1 = 1e-4 * al6061.density, mass_quad2 = 0.5e-4 * al6061.density;
            const double added = (scale - 1) * mass_quad2, total = 99 * mass_quad1 + mass_quad2;
            study.trend_holds("sec-2.3.5/obs-4/mass-scaling", std::abs(global / dt1 - 1) < 1e-12,
                        std::abs(global / dt1 - 1) < 1e-12 ? "global dt = Quad 1 dt" : fmt::format("global dt = {:.4f} us", global / us),
                        fmt::format("density x {:.3f} on the one Quad 2 element: global step {:.4f} -> {:.4f} us, "
                                    "added mass {:.2f} % of the mesh's",
                                    scale, dt2 / us, global / us, 100 * added / total));
        }

        // Tables as Markdown for the report, and the figures.
        study.write_markdown("table-2-1.md", table21.str());
        study.write_markdown("table-2-2.md", table22.str());
        study.plot();
    });
}
