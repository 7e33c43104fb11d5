// Dynamic relaxation (explicit/relaxation.hpp) against the linear static solution of the same mesh
// (assembly/static_solve.hpp) at a small load, and against itself: the relaxed state of an elastic
// body does not depend on the load path (one stage or several to the same load).
#include <cmath>

#include <gtest/gtest.h>

#include "assembly/static_solve.hpp"
#include "core/error.hpp"
#include "explicit/relaxation.hpp"
#include "explicit/tet_groups.hpp"
#include "mesh/finger.hpp"

using namespace fem;

namespace {

// A short elliptic rubber-like cantilever in tet10 (ν = 0.3 keeps the test cheap: the number of
// steps grows with the bulk wave speed), root clamped, tip loaded across along y.
struct Cantilever {
    Mesh mesh;
    ElasticMaterial material = ElasticMaterial::make("soft", 6.1e6, 0.3, 1000.0);
    std::vector<int> tip;
    double omega_1 = 0.0;        // Rayleigh quotient of the static deflection shape
    Vec3 linear_tip_per_newton;  // mean tip displacement per N of total load, linear

    Cantilever() {
        finger::EllipticCylinder g;
        g.length = 40e-3;
        mesh = finger::tet_finger(g, {.element_length = 6e-3, .order = 2, .match_mean_volume = false});
        tip = mesh.node_set("tip");
        Model lin(mesh);
        lin.add_solid_part("finger", material, {.mass = solid::MassKind::Lumped});
        lin.fix_node_set("root", kTranslations);
        const AssembledSystem sys = lin.assemble();
        std::vector<Vec3> f(mesh.node_count(), Vec3::Zero());
        for (int n : tip) f[n] = Vec3(0.0, 1.0 / tip.size(), 0.0);
        const std::vector<Vec3> u = solve_linear_static(sys, f);
        linear_tip_per_newton = mean(u);
        // omega_1^2 ~ f.u / (u^T M u) (Rayleigh quotient of the static shape, lumped masses).
        double fu = 0.0;
        for (int n = 0; n < mesh.node_count(); ++n) fu += f[n].dot(u[n]);
        Eigen::VectorXd ur = Eigen::VectorXd::Zero(sys.size());
        for (int n = 0; n < mesh.node_count(); ++n)
            for (int c = 0; c < 3; ++c)
                if (const int d = sys.dofs.dof(n, c); d >= 0)
                    if (const int r = sys.reduction.reduced_of_full[d]; r >= 0) ur(r) = u[n][c];
        const double umu = ur.dot(sys.mass.selfadjointView<Eigen::Lower>() * ur);
        omega_1 = std::sqrt(fu / umu);
    }
    Vec3 mean(const std::vector<Vec3>& field) const {
        Vec3 m = Vec3::Zero();
        for (int n : tip) m += field[n] / static_cast<double>(tip.size());
        return m;
    }
    RelaxationResult relax_to(const std::vector<double>& totals, double mass_scaling_dt = 0.0) const {
        ExplicitModel model(mesh);
        add_tets(model, "finger", material);
        model.fix(mesh.node_set("root"), Dofs::translations());
        RelaxationOptions o;
        o.omega_1 = omega_1;
        o.ke_fraction = 1e-8;
        o.solver.mass_scaling_dt = mass_scaling_dt;
        o.solver.print_summary = false;
        o.solver.progress = false;
        return relax(model, tip, Vec3(0.0, 1.0 / tip.size(), 0.0), totals, o);
    }
};

const Cantilever& cantilever() {
    static const Cantilever c;
    return c;
}

}  // namespace

TEST(Relaxation, SmallLoadGivesTheLinearStaticSolution) {
    const Cantilever& c = cantilever();
    const double load = 1e-3;  // N: tip deflection ~1e-5 of the length
    const RelaxationResult r = c.relax_to({load});
    ASSERT_EQ(r.stages.size(), 1u);
    const Vec3 dr = c.mean(r.stages[0].displacement), dl = load * c.linear_tip_per_newton;
    EXPECT_NEAR(dr.y(), dl.y(), 1e-3 * std::abs(dl.y())) << "relaxed " << dr.transpose() << ", linear " << dl.transpose();
    EXPECT_LT(r.stages[0].final_kinetic, 1e-8 * r.stages[0].peak_kinetic * 1.0001);
}

TEST(Relaxation, RelaxedStateDoesNotDependOnTheLoadPath) {
    // A large load (tip deflection ~20 % of the length, visibly nonlinear) in one stage and in three.
    const Cantilever& c = cantilever();
    const double big = 0.3 * 40e-3 / c.linear_tip_per_newton.y();
    const RelaxationResult one = c.relax_to({big}), three = c.relax_to({big / 3.0, 2.0 * big / 3.0, big});
    const Vec3 a = c.mean(one.stages.back().displacement), b = c.mean(three.stages.back().displacement);
    EXPECT_NEAR((a - b).norm(), 0.0, 2e-4 * a.norm());
    // Large deflection under a dead load across the beam: less than linear (the tip swings toward
    // the load's line) and with a shortening along the axis.
    EXPECT_LT(a.y(), 0.99 * big * c.linear_tip_per_newton.y());
    EXPECT_LT(a.z(), -0.01 * a.y());
}

TEST(Relaxation, MassScalingChangesThePathNotTheRelaxedState) {
    // The static state does not depend on the masses: selective mass scaling to twice the Table 2-1
    // step of the smallest tetrahedron (mass added to the small ones) takes fewer steps and relaxes
    // to the same large deflection. (On this uniform mesh the gain is small: much of the mesh is
    // scaled, omega_1 drops and the damping tuned to the unscaled omega_1 is overcritical; the
    // study's limbs, whose hinge knuckles hold the few small elements, gain more.)
    const Cantilever& c = cantilever();
    const double big = 0.3 * 40e-3 / c.linear_tip_per_newton.y();
    const RelaxationResult plain = c.relax_to({big});
    const double dt = plain.summary.controlling_dt;  // Table 2-1 step of the smallest element
    const RelaxationResult scaled = c.relax_to({big}, 2.0 * dt);
    EXPECT_GT(scaled.summary.added_mass_fraction, 0.0);
    EXPECT_LT(scaled.summary.steps, plain.summary.steps);
    const Vec3 a = c.mean(plain.stages.back().displacement), b = c.mean(scaled.stages.back().displacement);
    EXPECT_NEAR((a - b).norm(), 0.0, 2e-4 * a.norm()) << "plain " << a.transpose() << ", scaled " << b.transpose();
}

TEST(Relaxation, RejectsBadOptions) {
    const Cantilever& c = cantilever();
    ExplicitModel model(c.mesh);
    add_tets(model, "finger", c.material);
    RelaxationOptions o;  // omega_1 missing
    EXPECT_THROW(relax(model, c.tip, Vec3(0, 1, 0), {1.0}, o), InputError);
    o.omega_1 = 100.0;
    EXPECT_THROW(relax(model, c.tip, Vec3(0, 1, 0), {}, o), InputError);
}
