// Verification of the SIMP / OC topology optimizer (topopt/): filter partition of unity, the OC
// update meeting the volume, sensitivities against finite differences, input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.hpp"
#include "mesh/mesh.hpp"
#include "topopt/filter.hpp"
#include "topopt/model.hpp"
#include "topopt/simp.hpp"

using namespace fem;
using namespace fem::topopt;

namespace {

const ElasticMaterial kSteel = ElasticMaterial::make("steel", 207e9, 0.3, 7800);

// A small cantilever: nx x ny grid on [0, 2] x [0, 1], left edge clamped, load(s) on the right.
Model cantilever(int nx, int ny, ElementShape shape, int load_cases = 1) {
    const Mesh mesh = rectangle_quads(2.0, 1.0, nx, ny, shape);
    Model m = plane_stress_model(mesh, kSteel, 0.01);
    m.fix(mesh.node_sets.at("x0"), {0, 1}, "left edge");
    m.add_force(0, nearest_node(mesh, Vec3(2.0, 0.5, 0)), Vec3(0, -1000, 0));
    if (load_cases > 1) m.add_force(1, nearest_node(mesh, Vec3(2.0, 1.0, 0)), Vec3(700, 300, 0));
    return m;
}

TEST(TopoptFilter, WeightsArePartitionOfUnity) {
    const Mesh mesh = rectangle_quads(3.0, 1.0, 30, 10, ElementShape::Quad4);
    const Model m = plane_stress_model(mesh, kSteel, 0.01);
    for (double r : {0.05, 0.15, 0.32}) {
        const Filter f(m.centroid, m.volume, r);
        const Eigen::VectorXd ones = Eigen::VectorXd::Ones(m.element_count());
        EXPECT_LT((f.densities(ones) - ones).cwiseAbs().maxCoeff(), 1e-14) << "r = " << r;
        for (int k = 0; k < f.weights().outerSize(); ++k)
            for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(f.weights(), k); it; ++it)
                EXPECT_GE(it.value(), 0.0);
    }
    // r below the spacing (0.1): each element only sees itself.
    const Filter id(m.centroid, m.volume, 0.05);
    EXPECT_EQ(id.weights().nonZeros(), m.element_count());
    // r = 0.15 reaches the 4 edge neighbours (distance 0.1), not the diagonal ones (0.141 < 0.15: yes).
    const Filter f(m.centroid, m.volume, 0.15);
    const int interior = 5 * 30 + 15;
    EXPECT_EQ(f.weights().row(interior).nonZeros(), 9);
    // Hat weights: centre (0.15), edge (0.05), diagonal (0.15 - 0.1414); normalized.
    const double wc = 0.15, we = 0.05, wd = 0.15 - std::sqrt(0.02), sum = wc + 4 * we + 4 * wd;
    EXPECT_NEAR(f.weights().coeff(interior, interior), wc / sum, 1e-14);
    EXPECT_NEAR(f.weights().coeff(interior, interior + 1), we / sum, 1e-14);
    EXPECT_NEAR(f.weights().coeff(interior, interior + 31), wd / sum, 1e-14);
    EXPECT_THROW(Filter(m.centroid, m.volume, 0.0), InputError);
}

TEST(Simp, SensitivitiesMatchFiniteDifferences) {
    for (auto shape : {ElementShape::Quad4, ElementShape::Quad8}) {
        const Model m = cantilever(6, 3, shape, /*load_cases=*/2);
        StiffnessSolver solver(m);
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> U(0.2, 0.9);
        Eigen::VectorXd rho(m.element_count());
        for (auto& v : rho) v = U(rng);
        Eigen::VectorXd g, g2;
        const double c = compliance_and_gradient(m, solver, rho, 3.0, 1e-9, g);
        ASSERT_GT(c, 0);
        // Central differences: truncation O(h^2) is negligible at h = 1e-6; round-off of the solve
        // (~1e-13 c) divided by h is an absolute error shared by all elements, so it is bounded
        // relative to the largest sensitivity, not to a small one.
        const double gmax = g.cwiseAbs().maxCoeff();
        for (int e : {0, 4, 9, 17}) {
            const double h = 1e-6;
            Eigen::VectorXd rp = rho, rm = rho;
            rp(e) += h;
            rm(e) -= h;
            const double fd = (compliance_and_gradient(m, solver, rp, 3.0, 1e-9, g2) -
                               compliance_and_gradient(m, solver, rm, 3.0, 1e-9, g2)) / (2 * h);
            EXPECT_NEAR(g(e), fd, 1e-6 * std::abs(fd) + 1e-6 * gmax) << to_string(shape) << " element " << e;
        }
    }
}

TEST(Simp, DensityFilterChainRuleMatchesFiniteDifferences) {
    const Model m = cantilever(8, 4, ElementShape::Quad4);
    StiffnessSolver solver(m);
    const Filter f(m.centroid, m.volume, 0.4);
    Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(m.element_count(), 0.3, 0.8), g, g2;
    compliance_and_gradient(m, solver, f.densities(x), 3.0, 1e-9, g);
    const Eigen::VectorXd dx = f.backward(g);
    const double gmax = dx.cwiseAbs().maxCoeff();  // round-off bound, see the test above
    for (int e : {1, 10, 22}) {
        const double h = 1e-6;
        Eigen::VectorXd xp = x, xm = x;
        xp(e) += h;
        xm(e) -= h;
        const double fd = (compliance_and_gradient(m, solver, f.densities(xp), 3.0, 1e-9, g2) -
                           compliance_and_gradient(m, solver, f.densities(xm), 3.0, 1e-9, g2)) / (2 * h);
        EXPECT_NEAR(dx(e), fd, 1e-6 * std::abs(fd) + 1e-6 * gmax) << "element " << e;
    }
}

TEST(Simp, OcUpdateMeetsTheVolume) {
    for (auto kind : {FilterKind::None, FilterKind::Sensitivity, FilterKind::Density}) {
        Model m = cantilever(20, 10, ElementShape::Quad4);
        // A passive solid strip and a void hole: excluded from the volume, held at 1 and 0.
        m.mark(Region::Solid, [](const Vec3& c) { return c.x() > 1.9; });
        m.mark(Region::Void, [](const Vec3& c) { return (c - Vec3(1.0, 0.5, 0)).norm() < 0.2; });
        Settings s;
        s.volume_fraction = 0.4;
        s.filter = kind;
        s.filter_radius = 0.15;
        s.max_iterations = 3;
        const Result r = optimize(m, s);
        double v = 0, V = 0;
        for (int e = 0; e < m.element_count(); ++e) {
            if (m.region[e] == Region::Solid) { EXPECT_EQ(r.density[e], 1.0); }
            if (m.region[e] == Region::Void) { EXPECT_EQ(r.density[e], 0.0); }
            if (m.region[e] != Region::Design) continue;
            v += r.density[e] * m.volume[e];
            V += m.volume[e];
            EXPECT_GE(r.density[e], 0.0);
            EXPECT_LE(r.density[e], 1.0);
        }
        EXPECT_NEAR(v / V, 0.4, 1e-9) << "filter " << static_cast<int>(kind);
        EXPECT_NEAR(r.final_volume, v / V, 1e-12);
        // The starting design is uniform V*: its volume is recorded as the first history entry
        // (with the density filter the passive neighbours blur into it, so not exactly).
        if (kind != FilterKind::Density) { EXPECT_NEAR(r.volume.front(), 0.4, 1e-12); }
        EXPECT_EQ(r.iterations, 3);
        // Compliance must drop from the uniform start.
        EXPECT_LT(r.compliance.back(), r.compliance.front());
    }
}

TEST(Simp, SymmetricProblemGivesSymmetricDesignAndConverges) {
    // Load at mid-height of the free end: the optimum is symmetric about y = 0.5 (Michell-type
    // cantilever, thesis Fig 2-21).
    const Mesh mesh = rectangle_quads(2.0, 1.0, 40, 20, ElementShape::Quad4);
    Model m = plane_stress_model(mesh, kSteel, 0.01);
    m.fix(mesh.node_sets.at("x0"), {0, 1}, "left edge");
    m.add_force(0, nearest_node(mesh, Vec3(2.0, 0.5, 0)), Vec3(0, -1000, 0));
    Settings s;
    s.volume_fraction = 0.4;
    s.filter_radius = 0.075;
    const Result r = optimize(m, s);
    EXPECT_TRUE(r.converged);
    double asym = 0;
    for (int j = 0; j < 20; ++j)
        for (int i = 0; i < 40; ++i) asym = std::max(asym, std::abs(r.density[j * 40 + i] - r.density[(19 - j) * 40 + i]));
    EXPECT_LT(asym, 1e-6);
    // Compliance history decreases overall, and the design is mostly black and white.
    EXPECT_LT(r.compliance.back(), 0.5 * r.compliance.front());
}

TEST(Simp, InputErrorsNameTheCulprit) {
    Model m = cantilever(4, 2, ElementShape::Quad4);
    Settings s;
    s.filter_radius = 0.3;
    s.volume_fraction = 1.0;
    EXPECT_THROW(optimize(m, s), InputError);
    s.volume_fraction = 0.0;
    EXPECT_THROW(optimize(m, s), InputError);
    s.volume_fraction = 0.5;
    s.filter_radius = 0.0;
    EXPECT_THROW(optimize(m, s), InputError);
    s.filter_radius = 0.3;
    // A load on a node that does not exist.
    EXPECT_THROW(m.add_force(0, 1000, Vec3(1, 0, 0)), InputError);
    // Out-of-plane force on a plane model.
    EXPECT_THROW(m.add_force(0, 3, Vec3(0, 0, 1)), InputError);
    // Unsupported domain: singular stiffness.
    const Mesh mesh = rectangle_quads(2.0, 1.0, 4, 2, ElementShape::Quad4);
    Model free = plane_stress_model(mesh, kSteel, 0.01);
    free.fix(0, 0);
    free.fix(0, 1);  // one pinned node: the structure can still rotate
    free.add_force(0, 5, Vec3(0, 1, 0));
    try {
        optimize(free, s);
        ADD_FAILURE() << "a singular model was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos) << e.what();
    }
    // No load case at all.
    Model unloaded = plane_stress_model(mesh, kSteel, 0.01);
    unloaded.fix(mesh.node_sets.at("x0"), {0, 1}, "left");
    EXPECT_THROW(optimize(unloaded, s), InputError);
    // A support that selects no node.
    EXPECT_THROW(unloaded.fix(std::vector<int>{}, {0}, "empty set"), InputError);
}

TEST(TopoptMesh, CropKeepsOnlyUsedNodes) {
    const Mesh grid = rectangle_quads(2.0, 1.0, 20, 10, ElementShape::Quad8);
    const Mesh holed = crop(grid, [](const Vec3& c) { return (c - Vec3(1.0, 0.5, 0)).norm() > 0.25; });
    EXPECT_LT(holed.element_count(), grid.element_count());
    std::vector<int> used(holed.node_count(), 0);
    for (int n : holed.blocks.front().connectivity) used[n] = 1;
    for (int u : used) EXPECT_EQ(u, 1);
    validate(holed);
}

}  // namespace

namespace {

TEST(TopoptShellModel, FoldedPlateCantileverBendsLikeABeam) {
    // A 1 x 0.1 m plate, t = 0.01 m, in the x-z plane (normal y), clamped at x = 0, loaded by
    // P = 10 N in -y at the free end: Euler-Bernoulli d = P L^3 / (3 E I) (plate width 0.1 m, the
    // Poisson stiffening of a wide plate is small at b/L = 0.1): 3 % tolerance.
    Mesh mesh = rectangle_quads(1.0, 0.1, 40, 4, ElementShape::Quad4);
    for (auto& p : mesh.nodes) p = Vec3(p.x(), 0.0, p.y());
    Model m = shell_model(mesh, kSteel, 0.01);
    EXPECT_EQ(m.dofs_per_node, 6);
    m.fix(mesh.node_sets.at("x0"), {0, 1, 2, 3, 4, 5}, "clamp");
    const auto& tip = mesh.node_sets.at("x1");
    for (int n : tip) m.add_force(0, n, Vec3(0, -10.0 / tip.size(), 0));
    StiffnessSolver solver(m);
    const auto& u = solver.solve(Eigen::VectorXd::Ones(m.element_count()));
    double v = 0;
    for (int n : tip) v += u[0](6 * n + 1) / tip.size();
    const double I = 0.1 * 1e-6 / 12, d = 10.0 / (3 * 207e9 * I);
    EXPECT_NEAR(-v / d, 1.0, 0.03);
}

}  // namespace

TEST(TopoptFilter, RefusesARadiusWhoseWeightsCannotFit) {
    // 500 x 500 centroids and a radius that covers them all: 6e10 weights (2 TB), refused before
    // anything is allocated; the memory estimate of a normal radius (1.5 spacings) is about 9 neighbours.
    std::vector<Vec3> c;
    for (int j = 0; j < 500; ++j)
        for (int i = 0; i < 500; ++i) c.emplace_back(i, j, 0);
    const std::vector<double> v(c.size(), 1.0);
    EXPECT_THROW(Filter(c, v, 2000.0), InputError);
    EXPECT_NEAR(Filter::estimated_bytes(c, 1.5) / (32.0 * c.size()), 9.0, 0.1);
}

namespace {

TEST(HeavisideProjection, StepPropertiesAndSlope) {
    for (double beta : {1.0, 8.0, 64.0}) {
        const HeavisideProjection H{beta, 0.5};
        EXPECT_NEAR(H(0.0), 0.0, 1e-14);
        EXPECT_NEAR(H(1.0), 1.0, 1e-14);
        EXPECT_NEAR(H(0.5), 0.5, 1e-14);
        for (double t : {0.1, 0.45, 0.52, 0.9}) {
            const double h = 1e-6, fd = (H(t + h) - H(t - h)) / (2 * h);
            EXPECT_NEAR(H.slope(t), fd, 1e-6 * std::max(1.0, std::abs(fd))) << "beta " << beta << " t " << t;
        }
    }
    const HeavisideProjection sharp_step{64.0, 0.5};
    EXPECT_LT(sharp_step(0.4), 1e-3);  // sharp: grey 0.4 becomes void
}

TEST(HeavisideProjection, VectorFormsEqualTheScalarOnesBitForBit) {
    // optimize() projects whole designs with the vector forms; the designs must not depend on which.
    Eigen::VectorXd t(7);
    t << 0.0, 0.1, 0.4999, 0.5, 0.52, 0.9, 1.0;
    for (double beta : {1.0, 2.0, 32.0}) {
        const HeavisideProjection H{beta, 0.5};
        const Eigen::VectorXd h = H(t), s = H.slope(t);
        for (Eigen::Index i = 0; i < t.size(); ++i) {
            EXPECT_EQ(h(i), H(t(i))) << "beta " << beta << " t " << t(i);
            EXPECT_EQ(s(i), H.slope(t(i))) << "beta " << beta << " t " << t(i);
        }
    }
}

TEST(Simp, HeavisideProjectionGivesABlackAndWhiteDesign) {
    // The MBB half-beam (60 x 20): the density filter alone leaves grey transition layers; with the
    // projection and continuation to beta = 32 few elements stay grey, at the same volume.
    const Mesh mesh = rectangle_quads(60, 20, 60, 20, ElementShape::Quad4);
    Model m = plane_stress_model(mesh, ElasticMaterial::make("unit", 1.0, 0.3, 1.0), 1.0);
    m.fix(mesh.node_sets.at("x0"), {0}, "symmetry edge");
    m.fix(nearest_node(mesh, Vec3(60, 0, 0)), 1);
    m.add_force(0, nearest_node(mesh, Vec3(0, 20, 0)), Vec3(0, -1, 0));
    Settings s;
    s.volume_fraction = 0.5;
    s.filter = FilterKind::Density;
    s.filter_radius = 1.5;
    auto grey = [](const Result& r) {
        int n = 0;
        for (double v : r.density) n += v > 0.1 && v < 0.9;
        return double(n) / r.density.size();
    };
    const Result plain = optimize(m, s);
    // Continuation beta = 1, 2, ..., 32 (at most 50 iterations each), then 50 at beta = 32. At high
    // beta a few boundary elements keep alternating by 0.1-0.2 in rho (the OC update of a nearly
    // discrete design), so the loop ends on its iteration budget, not on the 0.01 change criterion.
    s.projection = Projection::Heaviside;
    s.max_iterations = 300;
    const Result sharp = optimize(m, s);
    EXPECT_EQ(sharp.beta.back(), 32.0);
    EXPECT_LT(sharp.compliance.back(), plain.compliance.back());  // the crisp design is also stiffer
    EXPECT_NEAR(sharp.final_volume, 0.5, 1e-9);
    EXPECT_LT(grey(sharp), 0.5 * grey(plain)) << grey(sharp) << " vs " << grey(plain);
    EXPECT_LT(grey(sharp), 0.05);
    s.filter = FilterKind::Sensitivity;
    EXPECT_THROW(optimize(m, s), InputError);
}

TEST(Simp, ProjectedDesignDoesNotAmplifyRoundOff) {
    // The MBB half-beam with projection to beta = 32, twice: the second load 1e-12 larger, a change
    // at the level of round-off. With the move limit on x alone (before 2026-12-04) whole elements
    // flipped between 0 and 1 at beta 16-32 and the two final designs differed in many elements; with
    // the limit on the physical densities (simp.hpp) the designs stay the same where it matters: no
    // element is solid (rho >= 0.5) in one and void in the other.
    const Mesh mesh = rectangle_quads(60, 20, 60, 20, ElementShape::Quad4);
    auto design = [&](double scale) {
        Model m = plane_stress_model(mesh, ElasticMaterial::make("unit", 1.0, 0.3, 1.0), 1.0);
        m.fix(mesh.node_sets.at("x0"), {0}, "symmetry edge");
        m.fix(nearest_node(mesh, Vec3(60, 0, 0)), 1);
        m.add_force(0, nearest_node(mesh, Vec3(0, 20, 0)), Vec3(0, -scale, 0));
        Settings s;
        s.volume_fraction = 0.5;
        s.filter = FilterKind::Density;
        s.filter_radius = 1.5;
        s.projection = Projection::Heaviside;
        s.max_iterations = 300;
        return optimize(m, s);
    };
    const Result a = design(1.0), b = design(1.0 + 1e-12);
    int solid_vs_void = 0;
    double largest = 0;
    for (std::size_t e = 0; e < a.density.size(); ++e) {
        solid_vs_void += (a.density[e] >= 0.5) != (b.density[e] >= 0.5);
        largest = std::max(largest, std::abs(a.density[e] - b.density[e]));
    }
    EXPECT_EQ(solid_vs_void, 0) << "largest density difference " << largest;
    EXPECT_NEAR(a.compliance.back(), b.compliance.back(), 1e-6 * a.compliance.back());
}

}  // namespace
