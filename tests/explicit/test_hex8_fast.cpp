// The per-cycle hexahedron kernel (element/hex8_explicit.hpp, Hex8Packed path) against independent
// references: its closed-form exact volume against the 2x2x2 Gauss volume, its V_e / A_emax against
// fem::cfl::hexahedron_length (thesis Table 2-1), its forces/energies against a plain Eigen
// transcription of the formulation (gamma vectors, no folding), the group's blocks of elements
// against the one-element kernel, the group's per-cycle critical step against
// fem::cfl::critical_time_step on every element, and the group's assembly (elements reordered
// for locality, coloured chunks scattering directly) against a plain element-by-element assembly,
// with the same bits on 1 and 2 threads.
//
// Tolerances (set before running): the quantities are mathematically equal and differ only by the
// order of the floating-point operations, so the relative differences are a few 1e-16 times the
// conditioning of the sums; 1e-12 for geometry (sums of O(1) terms on warped but valid elements)
// and 1e-10 for forces and energies at strains up to ~0.3 (terms cancel by up to ~1e3 in P B_a and
// in the hourglass displacements). The blocks do per lane the one-element kernel's operations in the
// same order, so they agree to the bit in this build; 1e-13 leaves room for a build that contracts
// a * b + c into FMAs differently in the two versions (-march=native).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <random>

#include "element/critical_time_step.hpp"
#include "element/hex8_explicit.hpp"
#include "explicit/groups.hpp"
#include "explicit/parallel.hpp"
#include "mesh/mesh.hpp"
#include "explicit_test_support.hpp"

using namespace fem;
using namespace fem::test;

namespace {

// A warped hexahedron: unit cube, every node moved randomly by up to `w`, then scaled, rotated and
// placed far from the origin (round-off of absolute coordinates).
std::array<Vec3, 8> warped_hex(std::mt19937& rng, double w, double scale, const Vec3& offset) {
    std::uniform_real_distribution<double> u(-w, w);
    const std::array<Vec3, 8> cube = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                                      Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
    const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
    std::array<Vec3, 8> X;
    for (int a = 0; a < 8; ++a) X[a] = offset + scale * (R * (cube[a] + Vec3(u(rng), u(rng), u(rng))));
    return X;
}

// The formulation of hex8_explicit.hpp written out directly with Eigen (gamma vectors, F^-1 from
// Eigen, Cauchy stress through P F^T): the reference the kernel must reproduce to round-off.
struct RefResult {
    std::array<Vec3, 8> f;
    double w = 0, hg = 0, visc = 0, trD = 0, vm = 0;
};
RefResult reference_kernel(const hex8::Hex8Reference& ref, const hex8::Hex8Material& mat,
                           const std::array<Vec3, 8>& u, const std::array<Vec3, 8>& v) {
    RefResult out;
    Mat3 H = Mat3::Zero(), Fdot = Mat3::Zero();
    for (int a = 0; a < 8; ++a) {
        H += u[a] * ref.B[a].transpose() / ref.volume;
        Fdot += v[a] * ref.B[a].transpose() / ref.volume;
    }
    const Mat3 F = Mat3::Identity() + H;
    const double J = F.determinant(), lnJ = std::log(J), mu = mat.mu, la = mat.lambda;
    const Mat3 FinvT = F.inverse().transpose();
    Mat3 P = mu * (F - FinvT) + la * lnJ * FinvT;
    out.w = ref.volume * (0.5 * mu * (F.squaredNorm() - 3.0) - mu * lnJ + 0.5 * la * lnJ * lnJ);
    out.vm = hex8::von_mises(P * F.transpose() / J);
    const Mat3 L = Fdot * F.inverse();
    const Mat3 D = 0.5 * (L + L.transpose());
    out.trD = L.trace();
    Mat3 sv = Mat3::Zero();
    if (mat.bulk_viscosity && out.trD < 0.0) {
        const double l = std::cbrt(J * ref.volume), c = std::sqrt((la + 2 * mu) / mat.density);
        const double q = mat.density / J * l * (mat.bulk.quadratic * l * out.trD * out.trD - mat.bulk.linear * c * out.trD);
        sv -= q * Mat3::Identity();
    }
    if (mat.rayleigh_beta > 0.0) sv += mat.rayleigh_beta * (2 * mu * D + la * out.trD * Mat3::Identity());
    out.visc = J * ref.volume * sv.cwiseProduct(D).sum();
    P += J * sv * FinvT;
    const double k = mat.hourglass_qm * 2.0 * mu * ref.hourglass_norm / 8.0;
    for (int a = 0; a < 8; ++a) out.f[a] = P * ref.B[a];
    for (int al = 0; al < 4; ++al) {
        Vec3 q = Vec3::Zero();
        for (int a = 0; a < 8; ++a) q += ref.gamma[al][a] * u[a];
        out.hg += 0.5 * k * q.squaredNorm();
        for (int a = 0; a < 8; ++a) out.f[a] += k * ref.gamma[al][a] * q;
    }
    return out;
}
}  // namespace

TEST(Hex8FastKernel, ExactVolumeEqualsGaussVolumeOnWarpedElements) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 200; ++trial) {
        const auto X = warped_hex(rng, 0.25, 0.01 + 0.001 * trial, Vec3(3.0, -2.0, 5.0));
        const double gauss = hex8::make_reference(X).volume;  // sum of det J at the 2x2x2 Gauss points
        EXPECT_NEAR(hex8::exact_volume(X), gauss, 1e-12 * gauss) << trial;
    }
    // A strongly warped (non-planar faces) element where det J varies a lot.
    std::array<Vec3, 8> X = {Vec3(0, 0, 0), Vec3(2, 0, 0.3), Vec3(2.2, 1.5, -0.2), Vec3(0, 1, 0),
                             Vec3(0.1, 0, 1), Vec3(1, 0.2, 1.4), Vec3(1.3, 1.1, 0.9), Vec3(-0.2, 1.2, 1.1)};
    const double gauss = hex8::make_reference(X).volume;
    EXPECT_NEAR(hex8::exact_volume(X), gauss, 1e-12 * gauss);
}

TEST(Hex8FastKernel, CharacteristicLengthEqualsTable21) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 200; ++trial) {
        const auto X = warped_hex(rng, 0.3, 0.002 * (1 + trial), Vec3(-1.0, 4.0, 0.5));
        const double expected = cfl::hexahedron_length(X);
        EXPECT_NEAR(hex8::characteristic_length(X), expected, 1e-12 * expected) << trial;
    }
}

TEST(Hex8FastKernel, ForcesAndEnergiesEqualTheDirectFormulation) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> g(-1.0, 1.0);
    int compressing = 0;
    for (int trial = 0; trial < 100; ++trial) {
        const auto X = warped_hex(rng, 0.2, 0.01, Vec3(0.5, 0.2, -0.3));
        const auto ref = hex8::make_reference(X);
        // Damping and bulk viscosity on and off in turn.
        const double beta = trial % 2 ? 1e-4 : 0.0;
        const auto mat = hex8::Hex8Material::from(kRubber, 0.1, beta, {}, trial % 3 != 0);
        Mat3 A;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) A(i, j) = 0.3 * g(rng);
        const Mat3 R = Eigen::AngleAxisd(0.1 * trial, Vec3(g(rng), g(rng), 1.0).normalized()).toRotationMatrix();
        std::array<Vec3, 8> u, v;
        for (int a = 0; a < 8; ++a) {
            // Large rotation and stretch plus a non-linear (hourglass-exciting) part.
            u[a] = R * (X[a] + A * (X[a] - X[0])) - X[a] + 0.002 * Vec3(g(rng), g(rng), g(rng));
            v[a] = Vec3(g(rng), g(rng), g(rng)) + (trial % 4 - 1.5) * (X[a] - X[0]) / 0.01;
        }
        const RefResult e = reference_kernel(ref, mat, u, v);
        hex8::Hex8Result r;
        hex8::internal_force(ref, mat, u, v, 0.0, r);
        ASSERT_FALSE(r.inverted) << trial;
        compressing += r.volumetric_strain_rate < 0.0;
        double fmax = 0.0;
        for (const auto& f : e.f) fmax = std::max(fmax, f.norm());
        for (int a = 0; a < 8; ++a) EXPECT_LT((r.force[a] - e.f[a]).norm(), 1e-10 * fmax) << trial << " node " << a;
        EXPECT_NEAR(r.strain_energy, e.w, 1e-10 * std::abs(e.w)) << trial;
        EXPECT_NEAR(r.hourglass_energy, e.hg, 1e-10 * e.hg) << trial;
        EXPECT_NEAR(r.viscous_power, e.visc, 1e-10 * std::abs(e.visc) + 1e-300) << trial;
        EXPECT_NEAR(r.volumetric_strain_rate, e.trD, 1e-10 * std::abs(e.trD)) << trial;
        EXPECT_NEAR(r.von_mises, e.vm, 1e-10 * e.vm) << trial;
    }
    EXPECT_GT(compressing, 20);  // the bulk-viscosity branch was exercised
    EXPECT_LT(compressing, 80);
}

// The kernel's own log1p (vectorizable, for ln J) against std::log1p: within 2 ulp (the method's
// bound is 1 ulp, libm's another) from tiny strains to J = 0.01 and J = 30.
TEST(Hex8FastKernel, KernelLog1pMatchesStdLog1p) {
    auto ulp = [](double y) { return std::nextafter(std::abs(y), INFINITY) - std::abs(y); };
    std::vector<double> xs;
    for (int p = 1; p <= 300; ++p)
        for (double m : {1.0, 3.7, 7.1}) {
            xs.push_back(m * std::pow(10.0, -p));
            xs.push_back(-m * std::pow(10.0, -p));
        }
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> wide(-0.99, 29.0), narrow(-0.3, 0.45);
    for (int i = 0; i < 200000; ++i) xs.push_back(i % 2 ? wide(rng) : narrow(rng));
    int worst_ulps = 0;
    for (double x : xs) {
        const double got = hex8::kernel_log1p(x), want = std::log1p(x);
        ASSERT_LE(std::abs(got - want), 2.0 * ulp(want)) << "x = " << x;
        if (want != 0.0) worst_ulps = std::max(worst_ulps, static_cast<int>(std::abs(got - want) / ulp(want)));
    }
    std::printf("kernel log1p vs std::log1p: at most %d ulp apart on %zu points\n", worst_ulps, xs.size());
}

namespace {
// A Hex8Group's forces recomputed element by element with the one-element kernel (the reference the
// blocked, coloured group must equal): assembled forces, energies, viscous power, and per element
// the von Mises stress and the Table 2-1 step (with the beta reduction) on the current nodes.
struct ElementByElement {
    std::vector<Vec3> f;
    double strain_energy = 0, hourglass_energy = 0, viscous_power = 0, fmax = 0;
    std::vector<double> von_mises, dt;
};
// mass_scale: the per-element density factors given to the group (selective mass scaling), if any.
ElementByElement element_by_element(const Hex8Group& group, const NodalState& s, const Hex8Options& opt,
                                    const std::vector<double>& mass_scale = {}) {
    const auto mat = hex8::Hex8Material::from(kRubber, opt.hourglass_qm, opt.rayleigh_beta, opt.bulk, opt.bulk_viscosity);
    ElementByElement out;
    out.f.assign(s.x.size(), Vec3::Zero());
    for (int e = 0; e < group.size(); ++e) {
        std::array<Vec3, 8> x, u, v;
        for (int a = 0; a < 8; ++a) {
            const int nd = group.connectivity(e)[a];
            x[a] = s.x[nd];
            u[a] = s.x[nd] - s.X[nd];
            v[a] = s.v[nd];
        }
        hex8::Hex8Result r;
        hex8::internal_force(group.reference(e), mat, u, v, 0.0, r);
        out.strain_energy += r.strain_energy;
        out.hourglass_energy += r.hourglass_energy;
        out.viscous_power += r.viscous_power;
        out.von_mises.push_back(r.von_mises);
        for (int a = 0; a < 8; ++a) {
            out.f[group.connectivity(e)[a]] += r.force[a];
            out.fmax = std::max(out.fmax, r.force[a].norm());
        }
        double dt = cfl::critical_time_step(ElementShape::Hex8, x, kRubber, r.volumetric_strain_rate, opt.bulk);
        if (!mass_scale.empty()) dt *= std::sqrt(mass_scale[e]);  // dt ~ sqrt(rho)
        dt *= std::sqrt(1.0 + (opt.rayleigh_beta / dt) * (opt.rayleigh_beta / dt)) - opt.rayleigh_beta / dt;
        out.dt.push_back(dt);
    }
    return out;
}
}  // namespace

// Hex8Group's per-cycle critical step (kernel V_e / A_emax) against fem::cfl::critical_time_step on
// each element's current nodes, with bulk viscosity, mass scaling and stiffness damping.
TEST(Hex8FastKernel, GroupTimeStepEqualsCriticalTimeStep) {
    Mesh mesh = box_hex8(0.03, 0.02, 0.02, 3, 2, 2, "blk");
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> g(-1.0, 1.0);
    for (auto& x : mesh.nodes) x += 0.0015 * Vec3(g(rng), g(rng), g(rng));
    for (double beta : {0.0, 2e-7}) {
        Hex8Options opt;
        opt.rayleigh_beta = beta;
        Hex8Group group(mesh, 0, kRubber, opt);
        std::vector<double> scale(group.size());
        for (auto& f : scale) f = 1.0 + 3.0 * (g(rng) + 1.0);
        group.set_mass_scaling(scale);
        NodalState s;
        s.X = mesh.nodes;
        for (const auto& X : mesh.nodes) s.x.push_back(X + 0.001 * Vec3(g(rng), g(rng), g(rng)));
        for (const auto& X : mesh.nodes) s.v.push_back(Vec3(g(rng), g(rng), g(rng)) - 100.0 * (X - Vec3(0.015, 0.01, 0.01)));
        s.f.assign(mesh.node_count(), Vec3::Zero());
        const auto res = group.internal_forces(s, true);
        const auto ref = element_by_element(group, s, opt, scale);
        const auto best = std::min_element(ref.dt.begin(), ref.dt.end());
        EXPECT_NEAR(res.dt_min, *best, 1e-12 * *best) << beta;
        EXPECT_EQ(res.dt_element, best - ref.dt.begin()) << beta;
    }
}

// The group's blocks of hex8::kLanes elements against the one-element kernel, element by element,
// on a mesh whose size is not a multiple of the block (the spare lanes of the last block) and with
// large deformation, compression and expansion: the same energies, stresses and assembled forces.
TEST(Hex8FastKernel, GroupBlocksEqualOneElementKernel) {
    Mesh mesh = box_hex8(0.03, 0.03, 0.01, 3, 3, 1, "blk");  // 9 elements: blocks of 8 and 1
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> g(-1.0, 1.0);
    for (auto& x : mesh.nodes) x += 0.001 * Vec3(g(rng), g(rng), g(rng));
    Hex8Options opt;
    opt.rayleigh_beta = 1e-6;
    Hex8Group group(mesh, 0, kRubber, opt);
    NodalState s;
    s.X = mesh.nodes;
    Mat3 A;
    A << 0.2, -0.1, 0.05, 0.1, -0.15, 0.0, 0.03, 0.08, 0.1;
    for (const auto& X : mesh.nodes) s.x.push_back(X + A * X + 0.0005 * Vec3(g(rng), g(rng), g(rng)));
    for (const auto& X : mesh.nodes) s.v.push_back(Vec3(g(rng), g(rng), g(rng)) + 50.0 * g(rng) * X);
    s.f.assign(mesh.node_count(), Vec3::Zero());
    const auto res = group.internal_forces(s, false);
    const ElementByElement ref = element_by_element(group, s, opt);
    const auto vm = group.element_stress();
    for (int e = 0; e < group.size(); ++e) EXPECT_NEAR(vm[e], ref.von_mises[e], 1e-13 * ref.von_mises[e]) << e;
    EXPECT_NEAR(res.internal_energy, ref.strain_energy, 1e-13 * ref.strain_energy);
    EXPECT_NEAR(res.hourglass_energy, ref.hourglass_energy, 1e-13 * ref.hourglass_energy);
    EXPECT_NEAR(res.viscous_power, ref.viscous_power, 1e-13 * std::abs(ref.viscous_power));
    for (int i = 0; i < mesh.node_count(); ++i) EXPECT_LT((s.f[i] - ref.f[i]).norm(), 1e-13 * ref.fmax) << i;
}

// hex8::gather (AVX-512 transposition on this machine, scalar stores elsewhere): every lane holds
// exactly x, x - X and v of its element's nodes, the spare lanes the last element's; the last node
// of the arrays included (its triple is loaded masked, nothing read past the end).
TEST(Hex8FastKernel, GatherPutsEachElementsNodesInItsLane) {
    const int nodes = 40;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> g(-1.0, 1.0);
    std::vector<Vec3> x, X, v;
    for (int i = 0; i < nodes; ++i) {
        X.push_back(Vec3(g(rng), g(rng), g(rng)));
        x.push_back(X.back() + 1e-3 * Vec3(g(rng), g(rng), g(rng)));
        v.push_back(Vec3(g(rng), g(rng), g(rng)));
    }
    std::vector<std::array<int, 8>> conn(8);
    std::uniform_int_distribution<int> pick(0, nodes - 1);
    for (auto& c : conn)
        for (int& n : c) n = pick(rng);
    conn[2][5] = nodes - 1;  // the arrays' last node
    for (int lanes : {8, 5, 1}) {
        alignas(hex8::kLanesAlign) hex8::Lanes xl[3][8], ul[3][8], vl[3][8];
        hex8::gather(x[0].data(), X[0].data(), v[0].data(), conn.data(), lanes, xl, ul, vl);
        for (int l = 0; l < hex8::kLanes; ++l)
            for (int a = 0; a < 8; ++a)
                for (int i = 0; i < 3; ++i) {
                    const int n = conn[std::min(l, lanes - 1)][a];
                    const double du = x[n][i] - X[n][i];
                    EXPECT_EQ(xl[i][a][l], x[n][i]) << lanes << " " << l << " " << a << " " << i;
                    const double u = ul[i][a][l];  // a copy: a vector-extension lane has no address
                    EXPECT_EQ(std::memcmp(&u, &du, sizeof du), 0) << lanes << " " << l << " " << a;
                    EXPECT_EQ(vl[i][a][l], v[n][i]) << lanes << " " << l << " " << a << " " << i;
                }
    }
}

// Chunk colouring (par::ChunkColouring): every chunk gets exactly one colour and two chunks of a
// colour share no node, on a mesh whose elements are in random order (many conflicts).
TEST(Hex8FastKernel, ChunkColouringSeparatesChunksOfAColour) {
    const Mesh mesh = box_hex8(1.0, 1.0, 1.0, 12, 10, 9, "blk");
    const ElementBlock& b = mesh.blocks[0];
    std::vector<std::array<int, 8>> conn(b.size());
    for (int e = 0; e < b.size(); ++e)
        for (int a = 0; a < 8; ++a) conn[e][a] = b.element(e)[a];
    std::mt19937 rng(4);
    std::shuffle(conn.begin(), conn.end(), rng);
    const auto col = par::ChunkColouring::build(conn, mesh.node_count(), 32);
    std::vector<int> seen(col.chunk_count(), 0);
    for (const auto& chunks : col.colours) {
        std::vector<int> owner(mesh.node_count(), -1);
        for (int c : chunks) {
            ++seen[c];
            const auto [e0, e1] = col.range(c);
            for (int e = e0; e < e1; ++e)
                for (int a : conn[e]) {
                    EXPECT_TRUE(owner[a] < 0 || owner[a] == c) << "node " << a << " in chunks " << owner[a] << ", " << c;
                    owner[a] = c;
                }
        }
    }
    for (int c = 0; c < col.chunk_count(); ++c) EXPECT_EQ(seen[c], 1) << c;
}

// The group's own element order (sorted for locality) and coloured direct scatter on a block whose
// elements are shuffled and large enough (4,480 > par::kParallelMin) for the parallel path: the
// same bits on 1 and 2 threads; forces, energies, stresses and the controlling element (in the
// block's order) as a plain element-by-element evaluation with the one-element kernel and
// fem::cfl::critical_time_step. Tolerances as above (1e-13: the same operations per element, the
// nodal sums in another order).
TEST(Hex8FastKernel, GroupOrderingAndThreadsKeepResults) {
    const Mesh box = box_hex8(0.2, 0.16, 0.14, 20, 16, 14, "blk");
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
    Hex8Options opt;
    opt.rayleigh_beta = 1e-7;
    Hex8Group group(mesh, 0, kRubber, opt);
    ASSERT_GT(group.size(), par::kParallelMin);
    NodalState s;
    s.X = mesh.nodes;
    for (const auto& X : mesh.nodes) s.x.push_back(X + 0.05 * Vec3(X.y(), -X.z(), X.x()) + 0.0003 * Vec3(g(rng), g(rng), g(rng)));
    for (const auto& X : mesh.nodes) s.v.push_back(Vec3(g(rng), g(rng), g(rng)) - 20.0 * (X - Vec3(0.1, 0.08, 0.07)));
    auto run = [&](int threads) {
        const int before = par::threads();
        par::set_threads(threads);
        s.f.assign(mesh.node_count(), Vec3::Zero());
        const auto r = group.internal_forces(s, true);
        par::set_threads(before);
        return std::make_pair(r, s.f);
    };
    const auto [r1, f1] = run(1);
    const auto vm1 = group.element_stress();
    const auto [r2, f2] = run(2);
    EXPECT_TRUE(f1 == f2);
    EXPECT_TRUE(vm1 == group.element_stress());
    EXPECT_EQ(r1.internal_energy, r2.internal_energy);
    EXPECT_EQ(r1.hourglass_energy, r2.hourglass_energy);
    EXPECT_EQ(r1.viscous_power, r2.viscous_power);
    EXPECT_EQ(r1.dt_min, r2.dt_min);
    EXPECT_EQ(r1.dt_element, r2.dt_element);
    EXPECT_EQ(r1.max_von_mises, r2.max_von_mises);

    // Element by element, in the block's order (the group reorders internally and maps back).
    for (int e = 0; e < group.size(); ++e)
        for (int a = 0; a < 8; ++a) ASSERT_EQ(group.connectivity(e)[a], mesh.blocks[0].element(e)[a]);
    const ElementByElement ref = element_by_element(group, s, opt);
    for (int e = 0; e < group.size(); ++e) EXPECT_NEAR(vm1[e], ref.von_mises[e], 1e-13 * ref.von_mises[e]) << e;
    const auto best = std::min_element(ref.dt.begin(), ref.dt.end());
    EXPECT_NEAR(r1.internal_energy, ref.strain_energy, 1e-13 * ref.strain_energy);
    EXPECT_NEAR(r1.hourglass_energy, ref.hourglass_energy, 1e-13 * ref.hourglass_energy);
    for (int i = 0; i < mesh.node_count(); ++i) EXPECT_LT((f1[i] - ref.f[i]).norm(), 1e-13 * ref.fmax) << i;
    EXPECT_NEAR(r1.dt_min, *best, 1e-12 * *best);
    EXPECT_EQ(r1.dt_element, best - ref.dt.begin());
}
