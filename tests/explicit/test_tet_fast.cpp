// The per-cycle tetrahedron kernels (element/tet_explicit.hpp: packed barycentric form, kLanes
// elements per pass) and the tet groups built on them (explicit/tet_groups.hpp: locality order,
// coloured direct scatter), against the direct Eigen formulation tet::internal_force(Reference, ...)
// element by element (the old path), and 1 against 2 threads.
//
// Stated round-off: the fast kernel takes H = F - I from the displacements, ln J by log1p of J - 1,
// the cofactor for F^-T and cbrt(V0) cbrt(J) for the bulk-viscosity length; the direct form takes F
// from the positions, Eigen's inverse, std::log and std::cbrt. Both are exact to ~1e-16 per
// operation; over the ~500 operations of a point they differ by ~1e-14 of the force scale, so the
// comparisons ask for 1e-12 (forces, against the largest element force; energies and powers,
// against their own size) and 1e-13 for the step (the same formula on the same corner nodes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <vector>

#include "element/critical_time_step.hpp"
#include "element/tet_explicit.hpp"
#include "explicit/parallel.hpp"
#include "explicit/tet_groups.hpp"
#include "explicit_test_support.hpp"

namespace fem {
using namespace fem::test;
namespace {


// A 10 mm tetrahedron near the reference one, randomly distorted; tet10 mid-edge nodes off their
// edges' midpoints (curved edges). At the origin: the direct form takes F from the positions, which
// far from the origin loses digits in proportion to the distance over the element size.
template <int N>
std::array<Vec3, N> random_element(std::mt19937& rng) {
    std::uniform_real_distribution<double> g(-1.0, 1.0);
    std::array<Vec3, N> X;
    const Vec3 corner[4] = {Vec3(0, 0, 0), Vec3(0.01, 0, 0), Vec3(0, 0.01, 0), Vec3(0, 0, 0.01)};
    for (int a = 0; a < 4; ++a) X[a] = corner[a] + 0.0015 * Vec3(g(rng), g(rng), g(rng));
    if constexpr (N == 10) {
        const int edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}};
        for (int e = 0; e < 6; ++e)
            X[4 + e] = 0.5 * (X[edge[e][0]] + X[edge[e][1]]) + 0.0006 * Vec3(g(rng), g(rng), g(rng));
    }
    return X;
}

template <int N, int Q>
tet::Reference<N, Q> reference_of(const std::array<Vec3, N>& X) {
    if constexpr (N == 4) return tet::make_tet4_reference(X);
    else return tet::make_tet10_reference(X);
}

// Deformed state: a finite homogeneous part (stretch and shear), a random part, and velocities that
// compress some elements and expand others (the bulk viscosity acts in compression only).
template <int N>
void random_state(const std::array<Vec3, N>& X, std::mt19937& rng, std::array<Vec3, N>& x, std::array<Vec3, N>& v) {
    std::uniform_real_distribution<double> g(-1.0, 1.0);
    Mat3 A;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) A(i, j) = 0.15 * g(rng);
    const double rate = 40.0 * g(rng);
    for (int a = 0; a < N; ++a) {
        x[a] = X[a] + A * (X[a] - X[0]) + 0.0004 * Vec3(g(rng), g(rng), g(rng));
        v[a] = rate * (X[a] - X[0]) + Vec3(g(rng), g(rng), g(rng));
    }
}

template <int N, int Q>
void kernel_against_direct_form() {
    std::mt19937 rng(N);
    for (double beta : {0.0, 3e-5}) {
        const hex8::Hex8Material mat = hex8::Hex8Material::from(kSoftRubber, 0.0, beta, {.quadratic = 1.5, .linear = 0.06}, true);
        for (int trial = 0; trial < 40; ++trial) {
            const auto X = random_element<N>(rng);
            const auto ref = reference_of<N, Q>(X);
            std::array<Vec3, N> x, v;
            random_state<N>(X, rng, x, v);
            tet::Result<N> direct;
            tet::internal_force(ref, mat, std::span<const Vec3>(x), std::span<const Vec3>(v), direct);
            ASSERT_GT(direct.min_jacobian, 0.0);
            double u[3][N], va[3][N];
            for (int a = 0; a < N; ++a)
                for (int i = 0; i < 3; ++i) {
                    u[i][a] = x[a][i] - X[a][i];
                    va[i][a] = v[a][i];
                }
            tet::TetKernelResult<N> fast;
            tet::internal_force(tet::pack(ref), mat, u, va, fast, true);
            double fmax = 0.0, fvmax = 0.0;
            for (int a = 0; a < N; ++a) {
                fmax = std::max(fmax, direct.force[a].norm());
                fvmax = std::max(fvmax, direct.viscous_force[a].norm());
            }
            for (int a = 0; a < N; ++a)
                for (int i = 0; i < 3; ++i) {
                    EXPECT_NEAR(fast.f[i][a], direct.force[a][i], 1e-12 * fmax) << trial << " node " << a;
                    EXPECT_NEAR(fast.fv[i][a], direct.viscous_force[a][i], 1e-12 * fmax) << trial << " node " << a;
                }
            EXPECT_NEAR(fast.strain_energy, direct.strain_energy, 1e-12 * direct.strain_energy) << trial;
            EXPECT_NEAR(fast.viscous_power, direct.viscous_power, 1e-12 * std::abs(direct.viscous_power) + 1e-300) << trial;
            EXPECT_NEAR(fast.volumetric_strain_rate, direct.volumetric_strain_rate,
                        1e-12 * std::abs(direct.volumetric_strain_rate)) << trial;
            EXPECT_NEAR(fast.min_jacobian, direct.min_jacobian, 1e-13) << trial;
            EXPECT_NEAR(std::sqrt(fast.von_mises_sq), direct.von_mises, 1e-12 * direct.von_mises) << trial;
            if (beta > 0.0 || direct.volumetric_strain_rate < 0.0) {
                EXPECT_GT(fvmax, 1e-6 * fmax) << trial;
            }
        }
    }
}

TEST(TetFastKernel, Tet4EqualsTheDirectFormulation) { kernel_against_direct_form<4, 1>(); }
TEST(TetFastKernel, Tet10EqualsTheDirectFormulation) { kernel_against_direct_form<10, 4>(); }

// kLanes different elements in one block: every lane has exactly the bits of the one-element kernel
// (the same operations per lane; no FMA in any clone).
template <int N, int Q>
void block_equals_one_element() {
    std::mt19937 rng(100 + N);
    const hex8::Hex8Material mat = hex8::Hex8Material::from(kSoftRubber, 0.0, 1e-5, {}, true);
    tet::TetPackedBlock<Q> block;
    alignas(hex8::kLanesAlign) hex8::Lanes u[3][N], v[3][N];
    std::vector<tet::TetKernelResult<N>> one(hex8::kLanes);
    for (int l = 0; l < hex8::kLanes; ++l) {
        const auto X = random_element<N>(rng);
        const auto packed = tet::pack(reference_of<N, Q>(X));
        tet::pack_lane(packed, l, block);
        std::array<Vec3, N> x, vel;
        random_state<N>(X, rng, x, vel);
        double ua[3][N], va[3][N];
        for (int a = 0; a < N; ++a)
            for (int i = 0; i < 3; ++i) {
                u[i][a][l] = ua[i][a] = x[a][i] - X[a][i];
                v[i][a][l] = va[i][a] = vel[a][i];
            }
        tet::internal_force(packed, mat, ua, va, one[l], true);
    }
    tet::TetKernelResultBlock<N> r;
    tet::internal_force(block, mat, u, v, r, true);
    for (int l = 0; l < hex8::kLanes; ++l) {
        for (int i = 0; i < 3; ++i)
            for (int a = 0; a < N; ++a) {
                EXPECT_EQ(r.f[i][a][l], one[l].f[i][a]) << l;
                EXPECT_EQ(r.fv[i][a][l], one[l].fv[i][a]) << l;
            }
        EXPECT_EQ(r.strain_energy[l], one[l].strain_energy) << l;
        EXPECT_EQ(r.viscous_power[l], one[l].viscous_power) << l;
        EXPECT_EQ(r.volumetric_strain_rate[l], one[l].volumetric_strain_rate) << l;
        EXPECT_EQ(r.min_jacobian[l], one[l].min_jacobian) << l;
        EXPECT_EQ(r.von_mises_sq[l], one[l].von_mises_sq) << l;
    }
}

TEST(TetFastKernel, Tet4BlockEqualsOneElementKernel) { block_equals_one_element<4, 1>(); }
TEST(TetFastKernel, Tet10BlockEqualsOneElementKernel) { block_equals_one_element<10, 4>(); }

// A straight-sided tet10 (mid-edge nodes at the midpoints) packed with one J0^-1 and weight
// (tet::pack_straight) gives the forces of the four-Jacobian packing to round-off (~1e-14 of the
// largest force); the randomly curved elements are not taken for straight. Blocks: every lane of
// the straight kernel has the bits of its one-element version.
TEST(TetFastKernel, StraightTet10SharesOneJacobian) {
    std::mt19937 rng(77);
    const hex8::Hex8Material mat = hex8::Hex8Material::from(kSoftRubber, 0.0, 3e-5, {.quadratic = 1.5, .linear = 0.06}, true);
    tet::TetPackedBlock<1> block;
    alignas(hex8::kLanesAlign) hex8::Lanes ub[3][10], vb[3][10];
    std::vector<tet::TetKernelResult<10>> one(hex8::kLanes);
    const int edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}};
    for (int trial = 0; trial < 40; ++trial) {
        auto X = random_element<10>(rng);
        EXPECT_FALSE(tet::straight_sided(X)) << trial;  // curved: the general packing stays
        for (int e = 0; e < 6; ++e) X[4 + e] = 0.5 * (X[edge[e][0]] + X[edge[e][1]]);
        ASSERT_TRUE(tet::straight_sided(X)) << trial;
        const auto ref = tet::make_tet10_reference(X);
        std::array<Vec3, 10> x, v;
        random_state<10>(X, rng, x, v);
        double u[3][10], va[3][10];
        for (int a = 0; a < 10; ++a)
            for (int i = 0; i < 3; ++i) {
                u[i][a] = x[a][i] - X[a][i];
                va[i][a] = v[a][i];
            }
        tet::TetKernelResult<10> four, shared;
        tet::internal_force(tet::pack(ref), mat, u, va, four, true);
        const auto packed = tet::pack_straight(ref);
        tet::internal_force(packed, mat, u, va, shared, true);
        double fmax = 0.0;
        for (int a = 0; a < 10; ++a)
            for (int i = 0; i < 3; ++i) fmax = std::max(fmax, std::abs(four.f[i][a]));
        for (int a = 0; a < 10; ++a)
            for (int i = 0; i < 3; ++i) {
                EXPECT_NEAR(shared.f[i][a], four.f[i][a], 1e-14 * fmax) << trial << " node " << a;
                EXPECT_NEAR(shared.fv[i][a], four.fv[i][a], 1e-14 * fmax) << trial << " node " << a;
            }
        EXPECT_NEAR(shared.strain_energy, four.strain_energy, 1e-14 * four.strain_energy) << trial;
        EXPECT_NEAR(shared.viscous_power, four.viscous_power, 1e-14 * std::abs(four.viscous_power) + 1e-300) << trial;
        EXPECT_NEAR(shared.min_jacobian, four.min_jacobian, 1e-14) << trial;
        EXPECT_NEAR(shared.von_mises_sq, four.von_mises_sq, 1e-14 * four.von_mises_sq) << trial;
        const int l = trial % hex8::kLanes;
        tet::pack_lane(packed, l, block);
        for (int a = 0; a < 10; ++a)
            for (int i = 0; i < 3; ++i) {
                ub[i][a][l] = u[i][a];
                vb[i][a][l] = va[i][a];
            }
        one[l] = shared;
        if (l == hex8::kLanes - 1) {
            tet::TetKernelResultBlock<10> r;
            tet::internal_force(block, mat, ub, vb, r, true);
            for (int k = 0; k < hex8::kLanes; ++k) {
                for (int i = 0; i < 3; ++i)
                    for (int a = 0; a < 10; ++a) {
                        EXPECT_EQ(r.f[i][a][k], one[k].f[i][a]) << k;
                        EXPECT_EQ(r.fv[i][a][k], one[k].fv[i][a]) << k;
                    }
                EXPECT_EQ(r.strain_energy[k], one[k].strain_energy) << k;
                EXPECT_EQ(r.von_mises_sq[k], one[k].von_mises_sq) << k;
            }
        }
    }
}

TEST(TetFastKernel, CharacteristicLengthEqualsTable21) {
    std::mt19937 rng(3);
    for (int trial = 0; trial < 100; ++trial) {
        const auto X = random_element<4>(rng);
        double x[3][4];
        for (int a = 0; a < 4; ++a)
            for (int i = 0; i < 3; ++i) x[i][a] = X[a][i];
        const double table = cfl::tetrahedron_length(X);
        EXPECT_NEAR(tet::characteristic_length(x), table, 1e-14 * table) << trial;
    }
}

// The tet10's step length on its integration points (tet::characteristic_length_tet10): at rest and
// under any affine deformation it is the corner tetrahedron's Table 2-1 length; on a sliver of the
// chicken_shackling grasp model (Step 3, bird element 7890 at 0.85 s: its corners flattened to 0.57
// of their volume while the element's points kept det F 0.98..1.02) the element's highest frequency
// (its tangent stiffness at that state by central differences of the forces, against its HRZ
// masses) follows the integration-point length, not the corners' altitude, which would cut the
// step by ~43 %.
TEST(TetFastKernel, Tet10StepLengthFollowsTheIntegrationPointsNotTheCorners) {
    // Reference and current positions [mm] of the grasp model's element (Gmsh node order), relative
    // to their corners' centroids.
    const double ref_mm[10][3] = {{0.303146, 1.663044, -1.819489}, {-0.096907, -1.416814, 3.180511}, {-2.536326, 1.053340, 0.175027},
                                  {2.330087, -1.299569, -1.536050}, {0.103119, 0.123115, 0.680511},  {-1.316617, -0.181737, 1.677769},
                                  {-1.116590, 1.358192, -0.822231}, {1.316617, 0.181737, -1.677769}, {-0.103119, -0.123115, -0.680511},
                                  {1.116590, -1.358192, 0.822231}};
    const double cur_mm[10][3] = {{1.074406, 1.150759, -1.823449}, {-1.241566, -1.195381, 3.006440}, {-1.118144, 2.509061, 0.258059},
                                  {1.285304, -2.464439, -1.441049}, {0.010233, -0.021237, 0.735674},  {-1.294109, 0.653542, 1.711038},
                                  {-0.049733, 1.791621, -0.780806}, {1.084266, -0.709855, -1.614071}, {-0.263949, -0.050550, -0.636335},
                                  {0.031837, -1.792964, 0.775682}};
    std::array<Vec3, 10> X, x;
    for (int a = 0; a < 10; ++a) {
        X[a] = 1e-3 * Vec3(ref_mm[a][0], ref_mm[a][1], ref_mm[a][2]);
        x[a] = 1e-3 * Vec3(cur_mm[a][0], cur_mm[a][1], cur_mm[a][2]);
    }
    const int edge[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {2, 3}, {1, 3}};  // straight-sided: the printed digits aside
    for (int e = 0; e < 6; ++e) X[4 + e] = 0.5 * (X[edge[e][0]] + X[edge[e][1]]);
    auto length = [&](const std::array<Vec3, 10>& at) {
        double xc[3][4], u[3][10];
        for (int a = 0; a < 10; ++a)
            for (int i = 0; i < 3; ++i) {
                if (a < 4) xc[i][a] = at[a][i];
                u[i][a] = at[a][i] - X[a][i];
            }
        return tet::characteristic_length_tet10(xc, u);
    };
    const double corners_ref = cfl::tetrahedron_length({X[0], X[1], X[2], X[3]});
    const double corners_now = cfl::tetrahedron_length({x[0], x[1], x[2], x[3]});
    EXPECT_NEAR(length(X), corners_ref, 1e-13 * corners_ref);  // at rest: the Table 2-1 length
    // An affine deformation (stretch, shear, rotation) of the straight-sided element: the corners' length.
    Mat3 F;
    F << 1.2, 0.3, -0.1, 0.05, 0.7, 0.2, -0.15, 0.1, 0.9;
    std::array<Vec3, 10> affine;
    for (int a = 0; a < 10; ++a) affine[a] = F * X[a] + Vec3(0.01, -0.02, 0.03);
    EXPECT_NEAR(length(affine), cfl::tetrahedron_length({affine[0], affine[1], affine[2], affine[3]}), 1e-12 * corners_ref);
    // The sliver: the corners lost 43 % of their altitude, the points did not.
    EXPECT_LT(corners_now / corners_ref, 0.6);
    const double points_now = length(x);
    EXPECT_GT(points_now / corners_ref, 0.9);
    // Its highest frequency: the tangent stiffness at x by central differences of the forces.
    const ElasticMaterial bird = ElasticMaterial::make("chicken", 6.1e6, 0.49, 1135.0);  // chicken::material
    const auto ref = tet::make_tet10_reference(X);
    const hex8::Hex8Material mat = hex8::Hex8Material::from(bird);
    const std::array<double, 10> m = tet::tet10_lumped_mass(X, bird.density);
    auto omega_at = [&](const std::array<Vec3, 10>& at) {
        Eigen::MatrixXd K(30, 30);
        std::array<Vec3, 10> v;  // at rest (Eigen vectors are not zeroed by {}: garbage velocities would add bulk viscosity)
        v.fill(Vec3::Zero());
        const double h = 1e-9;
        for (int b = 0; b < 10; ++b)
            for (int j = 0; j < 3; ++j) {
                auto plus = at, minus = at;
                plus[b][j] += h, minus[b][j] -= h;
                tet::Result<10> fp, fm;
                tet::internal_force(ref, mat, std::span<const Vec3>(plus), std::span<const Vec3>(v), fp);
                tet::internal_force(ref, mat, std::span<const Vec3>(minus), std::span<const Vec3>(v), fm);
                for (int a = 0; a < 10; ++a)
                    for (int i = 0; i < 3; ++i) K(3 * a + i, 3 * b + j) = (fp.force[a][i] - fm.force[a][i]) / (2.0 * h);
            }
        return tet::element_omega_max(0.5 * (K + K.transpose()), m);
    };
    const double frequency_ratio = omega_at(X) / omega_at(x);  // the step's ratio, now over at rest
    EXPECT_NEAR(frequency_ratio, points_now / corners_ref, 0.1);
    EXPECT_GT(frequency_ratio, 1.5 * corners_now / corners_ref);
    std::printf("sliver: corner length ratio %.3f, integration-point length ratio %.3f, 2/omega ratio %.3f\n",
                corners_now / corners_ref, points_now / corners_ref, frequency_ratio);
}

// The group's element order and coloured direct scatter on a block whose elements are shuffled and
// large enough for the parallel path: the same bits on 1 and 2 threads; forces, energies, stresses,
// the step and the controlling element (in the block's order) as an element-by-element evaluation
// with the direct formulation and fem::cfl::critical_time_step (the old path), to the round-off
// stated at the top. With stiffness damping, bulk viscosity in compression and expansion, selective
// mass scaling and a stability factor.
template <class Group>
void group_against_element_by_element(ElementShape shape) {
    constexpr int N = std::tuple_size_v<std::decay_t<decltype(std::declval<Group>().connectivity(0))>>;
    const Mesh box = box_tets(0.2, 0.16, 0.14, 10, 8, 7, shape, "blk");
    Mesh mesh = box;
    {
        const ElementBlock& b = box.blocks[0];
        std::vector<int> perm(b.size());
        for (int e = 0; e < b.size(); ++e) perm[e] = e;
        std::mt19937 rng(21);
        std::shuffle(perm.begin(), perm.end(), rng);
        mesh.blocks[0].connectivity.clear();
        for (int e : perm) mesh.blocks[0].add(b.element(e));
    }
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> g(-1.0, 1.0);
    for (auto& x : mesh.nodes) x += 0.001 * Vec3(g(rng), g(rng), g(rng));
    if constexpr (N == 10) {
        // Straight-sided tet10s in the half x < 0.1 (mid-edge nodes back on their edges' midpoints):
        // whole blocks there take the one-Jacobian packing (tet::pack_straight), the rest four.
        const int edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}};
        for (int e = 0; e < mesh.blocks[0].size(); ++e) {
            const auto c = mesh.blocks[0].element(e);
            if (mesh.nodes[c[0]].x() + mesh.nodes[c[1]].x() + mesh.nodes[c[2]].x() + mesh.nodes[c[3]].x() > 0.4) continue;
            for (int k = 0; k < 6; ++k) mesh.nodes[c[4 + k]] = 0.5 * (mesh.nodes[c[edge[k][0]]] + mesh.nodes[c[edge[k][1]]]);
        }
    }
    const TetGroupOptions opt{.rayleigh_beta = 1e-6};
    Group group(mesh, 0, kSoftRubber, opt);
    ASSERT_GT(group.size(), 1024);
    if constexpr (N == 10) {
        EXPECT_GT(group.straight_blocks(), 0);
        EXPECT_LT(group.straight_blocks(), (group.size() + hex8::kLanes - 1) / hex8::kLanes);
    }
    std::vector<double> scale(group.size());
    for (auto& f : scale) f = 1.0 + (g(rng) + 1.0);
    group.set_mass_scaling(scale);
    ASSERT_TRUE(group.set_stability_factor(0.7));
    NodalState s;
    s.X = mesh.nodes;
    for (const auto& X : mesh.nodes)
        s.x.push_back(X + 0.05 * Vec3(X.y(), -X.z(), X.x()) + 0.0003 * Vec3(g(rng), g(rng), g(rng)));
    for (const auto& X : mesh.nodes) s.v.push_back(Vec3(g(rng), g(rng), g(rng)) - 20.0 * (X - Vec3(0.1, 0.08, 0.07)));
    auto run = [&](int threads) {
        const int before = par::threads();
        par::set_threads(threads);
        s.f.assign(mesh.node_count(), Vec3::Zero());
        s.fv.assign(mesh.node_count(), Vec3::Zero());
        const auto r = group.internal_forces(s, true);
        par::set_threads(before);
        return std::make_tuple(r, s.f, s.fv);
    };
    const auto [r1, f1, fv1] = run(1);
    const auto vm1 = group.element_stress();
    const auto [r2, f2, fv2] = run(2);
    EXPECT_TRUE(f1 == f2);
    EXPECT_TRUE(fv1 == fv2);
    EXPECT_TRUE(vm1 == group.element_stress());
    EXPECT_EQ(r1.internal_energy, r2.internal_energy);
    EXPECT_EQ(r1.viscous_power, r2.viscous_power);
    EXPECT_EQ(r1.dt_min, r2.dt_min);
    EXPECT_EQ(r1.dt_element, r2.dt_element);
    EXPECT_EQ(r1.max_von_mises, r2.max_von_mises);

    // Element by element with the direct formulation, in the block's order.
    std::vector<Vec3> f(mesh.node_count(), Vec3::Zero()), fv(mesh.node_count(), Vec3::Zero());
    double energy = 0.0, power = 0.0, fmax = 0.0, dt_min = 1e300;
    int dt_element = -1;
    for (int e = 0; e < group.size(); ++e) {
        std::array<Vec3, N> x, v;
        for (int a = 0; a < N; ++a) {
            ASSERT_EQ(group.connectivity(e)[a], mesh.blocks[0].element(e)[a]);
            x[a] = s.x[group.connectivity(e)[a]];
            v[a] = s.v[group.connectivity(e)[a]];
        }
        tet::Result<N> r;
        tet::internal_force(group.reference(e), group.kernel_material(), std::span<const Vec3>(x),
                            std::span<const Vec3>(v), r);
        for (int a = 0; a < N; ++a) {
            f[group.connectivity(e)[a]] += r.force[a];
            fv[group.connectivity(e)[a]] += r.viscous_force[a];
            fmax = std::max(fmax, r.force[a].norm());
        }
        energy += r.strain_energy;
        power += r.viscous_power;
        EXPECT_NEAR(vm1[e], r.von_mises, 1e-12 * r.von_mises) << e;
        // The element's own limit carried by its Table 2-1 step (tet_groups.hpp), mass scaling, the
        // factor; the tet10's step on its integration points' deformation (critical_time_step_tet10).
        double table = cfl::critical_time_step(shape, x, kSoftRubber, r.volumetric_strain_rate, opt.bulk);
        if constexpr (N == 10) {
            double xc[3][4], u[3][10];
            for (int a = 0; a < N; ++a)
                for (int i = 0; i < 3; ++i) {
                    if (a < 4) xc[i][a] = x[a][i];
                    u[i][a] = x[a][i] - s.X[group.connectivity(e)[a]][i];
                }
            table = cfl::solid_time_step(tet::characteristic_length_tet10(xc, u), cfl::wave_speed(shape, kSoftRubber),
                                         r.volumetric_strain_rate, opt.bulk);
        }
        double dt = 0.7 * group.element_stability_ratio(e) * table * std::sqrt(scale[e]);
        const double xi = opt.rayleigh_beta / dt;
        dt *= std::sqrt(1.0 + xi * xi) - xi;
        if (dt < dt_min) {
            dt_min = dt;
            dt_element = e;
        }
    }
    EXPECT_NEAR(r1.internal_energy, energy, 1e-12 * energy);
    EXPECT_NEAR(r1.viscous_power, power, 1e-12 * std::abs(power));
    for (int i = 0; i < mesh.node_count(); ++i) {
        EXPECT_LT((f1[i] - f[i]).norm(), 1e-12 * fmax) << i;
        EXPECT_LT((fv1[i] - fv[i]).norm(), 1e-12 * fmax) << i;
    }
    EXPECT_NEAR(r1.dt_min, dt_min, 1e-13 * dt_min);
    EXPECT_EQ(r1.dt_element, dt_element);
}

// tet::gather (AVX-512 transposition where the processor has it): every lane holds exactly its
// element's nodal values, x - X by one IEEE subtraction, and the spare lanes of a short block repeat
// its last element. The last node of the arrays is used (the masked loads must not read past it).
template <int N>
void gather_puts_each_element_in_its_lane() {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> g(-1.0, 1.0);
    const int nodes = 40;
    std::vector<double> xs(3 * nodes), Xs(3 * nodes), vs(3 * nodes);
    for (auto* a : {&xs, &Xs, &vs})
        for (double& d : *a) d = g(rng);
    std::vector<std::array<int, N>> conn(hex8::kLanes);
    std::uniform_int_distribution<int> pick(0, nodes - 1);
    for (auto& c : conn)
        for (int& n : c) n = pick(rng);
    conn[2][N - 1] = nodes - 1;
    for (int lanes : {hex8::kLanes, 3}) {
        alignas(hex8::kLanesAlign) hex8::Lanes x[3][4], u[3][N], v[3][N];
        tet::gather<N>(xs.data(), Xs.data(), vs.data(), conn.data(), lanes, x, u, v);
        for (int l = 0; l < hex8::kLanes; ++l) {
            const auto& c = conn[std::min(l, lanes - 1)];
            for (int a = 0; a < N; ++a)
                for (int i = 0; i < 3; ++i) {
                    const std::size_t o = 3 * static_cast<std::size_t>(c[a]) + i;
                    EXPECT_EQ(u[i][a][l], xs[o] - Xs[o]) << lanes << " " << l << " " << a;
                    EXPECT_EQ(v[i][a][l], vs[o]) << lanes << " " << l << " " << a;
                    if (a < 4) {
                        EXPECT_EQ(x[i][a][l], xs[o]) << lanes << " " << l << " " << a;
                    }
                }
        }
    }
}
TEST(TetFastKernel, Tet4GatherPutsEachElementInItsLane) { gather_puts_each_element_in_its_lane<4>(); }
TEST(TetFastKernel, Tet10GatherPutsEachElementInItsLane) { gather_puts_each_element_in_its_lane<10>(); }

TEST(TetFastKernel, Tet4GroupOrderingAndThreadsKeepResults) { group_against_element_by_element<Tet4Group>(ElementShape::Tet4); }
TEST(TetFastKernel, Tet10GroupOrderingAndThreadsKeepResults) {
    group_against_element_by_element<Tet10Group>(ElementShape::Tet10);
}

}  // namespace
}  // namespace fem
