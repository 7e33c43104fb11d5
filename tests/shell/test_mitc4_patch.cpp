// Patch tests of MacNeal and Harder (1985): a 0.24 x 0.12 rectangle cut into five distorted
// quadrilaterals. Displacements of a constant-strain (membrane) or constant-curvature (bending)
// field are prescribed on the four outer nodes; the interior nodes must follow the field exactly and
// the strain energy must equal the closed form. Run flat in the x-y plane and rotated in space, so
// that the element's global-axes rotations are exercised as well.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "shell_test_model.hpp"

using namespace fem;
using namespace shelltest;

namespace {
const ElasticMaterial kMat = ElasticMaterial::make("MacNeal-Harder", 1.0e6, 0.25, 1.0);

DenseShellModel patch(const Mat3& Q) {
    DenseShellModel m;
    const double xy[8][2] = {{0, 0},       {0.24, 0},     {0.24, 0.12},  {0, 0.12},
                             {0.04, 0.02}, {0.18, 0.03}, {0.16, 0.08}, {0.08, 0.08}};
    for (auto& p : xy) m.nodes.push_back(Q * Vec3(p[0], p[1], 0));
    m.quads = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}, {4, 5, 6, 7}};
    return m;
}

struct Field {
    Vec3 u, theta;  // local (patch-plane) displacement and rotation
};

// Prescribes the local field on the outer nodes (0-3) and solves; returns the interior error and the
// strain energy. `local_fixed` lists local DOF (0..5) held at the field's value on every node (the
// uncoupled half of the problem).
struct PatchResult {
    double max_error, energy, scale;
};

template <class F>
PatchResult run_patch(const Mat3& Q, double t, F field, std::vector<int> local_fixed_everywhere) {
    auto m = patch(Q);
    m.assemble(t, kMat);
    const int n = m.dofs();
    // Work in local DOF: transform K into the patch frame so that "fix w" means the patch normal.
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n / 3; ++i) T.block<3, 3>(3 * i, 3 * i) = Q;
    const Eigen::MatrixXd Kl = T.transpose() * m.K * T;
    Eigen::VectorXd exact(n);
    std::vector<bool> fixed(n, false);
    for (int k = 0; k < 8; ++k) {
        const Vec3 xl = Q.transpose() * m.nodes[k];
        const Field f = field(xl.x(), xl.y());
        exact.segment<3>(6 * k) = f.u;
        exact.segment<3>(6 * k + 3) = f.theta;
        for (int d = 0; d < 6; ++d) fixed[6 * k + d] = k < 4;
        for (int d : local_fixed_everywhere) fixed[6 * k + d] = true;
    }
    const Partition p(fixed);
    const Eigen::VectorXd u = solve_static(Kl, Eigen::VectorXd::Zero(n), p, exact);
    return {(u - exact).cwiseAbs().maxCoeff(), 0.5 * u.dot(Kl * u), exact.cwiseAbs().maxCoeff()};
}

Mat3 rotation(int which) {
    return which == 0 ? Mat3::Identity() : Mat3(Eigen::AngleAxisd(1.1, Vec3(0.3, -1, 2).normalized()));
}
}  // namespace

class Mitc4Patch : public ::testing::TestWithParam<int> {};

TEST_P(Mitc4Patch, MembraneConstantStrain) {
    // u = 1e-3 (x + y/2), v = 1e-3 (y + x/2): eps_x = eps_y = gamma_xy = 1e-3, no rotation.
    const double t = 0.001, E = kMat.youngs_modulus, nu = kMat.poissons_ratio;
    const auto r = run_patch(rotation(GetParam()), t,
                             [](double x, double y) {
                                 return Field{Vec3(1e-3 * (x + y / 2), 1e-3 * (y + x / 2), 0), Vec3::Zero()};
                             },
                             {2, 3, 4});  // w, rx, ry: the bending half is uncoupled for a flat patch
    EXPECT_LT(r.max_error, 1e-9 * r.scale);
    const double e = 1e-3, c = E / (1 - nu * nu);
    const double density = 0.5 * c * (e * e + 2 * nu * e * e + e * e) + 0.5 * (E / (2 * (1 + nu))) * e * e;
    const double exact_energy = density * t * 0.24 * 0.12;
    EXPECT_NEAR(r.energy, exact_energy, 1e-8 * exact_energy);
}

TEST_P(Mitc4Patch, BendingConstantCurvature) {
    // w = 1e-3 (x^2 + x y + y^2) / 2, Kirchhoff rotations theta_x = w_y, theta_y = -w_x: curvatures
    // w_xx = w_yy = 1e-3, 2 w_xy = 1e-3, no transverse shear. Thin plate (t = 0.001, span/t = 240).
    const double t = 0.001, E = kMat.youngs_modulus, nu = kMat.poissons_ratio;
    const auto r = run_patch(rotation(GetParam()), t,
                             [](double x, double y) {
                                 const double w = 1e-3 * (x * x + x * y + y * y) / 2;
                                 const double wx = 1e-3 * (2 * x + y) / 2, wy = 1e-3 * (x + 2 * y) / 2;
                                 return Field{Vec3(0, 0, w), Vec3(wy, -wx, 0)};
                             },
                             {0, 1, 5});  // u, v, rz: the membrane half
    EXPECT_LT(r.max_error, 1e-7 * r.scale);
    const double k = 1e-3, Db = E * t * t * t / (12 * (1 - nu * nu));
    const double density = 0.5 * Db * (k * k + 2 * nu * k * k + k * k + 0.5 * (1 - nu) * k * k);
    const double exact_energy = density * 0.24 * 0.12;
    EXPECT_NEAR(r.energy, exact_energy, 1e-6 * exact_energy);
}

INSTANTIATE_TEST_SUITE_P(FlatAndRotated, Mitc4Patch, ::testing::Values(0, 1));
