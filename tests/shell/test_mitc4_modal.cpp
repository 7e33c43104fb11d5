// MITC4 through the library's sparse assembly (lib/assembly, 6-DOF nodes) and modal solver
// (lib/modal): the same results as the dense test assembly, and flat or folded shell assemblies with
// exactly six rigid-body modes (the drilling penalty leaves no spurious zero-energy mode).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "assembly/model.hpp"
#include "element/shell_mitc4.hpp"
#include "mesh/mesh.hpp"
#include "modal/modal.hpp"
#include "shell_test_model.hpp"
#include "../test_materials.hpp"

using namespace fem;
using fem::test::kShellSteel;

namespace {

ElementKernel mitc4_kernel(double t, bool lumped = false) {
    return [t, lumped](std::span<const Vec3> x, int) {
        const auto s = shell::mitc4_matrices({x[0], x[1], x[2], x[3]}, t, kShellSteel);
        return ElementMatrices{s.stiffness, lumped ? s.lumped_mass : s.consistent_mass};
    };
}

// Two rectangles meeting at a right-angled fold along y (x = 0): a vertical leg (x = 0, z in [0, a])
// and a horizontal one (z = a, x in [0, b]); nodes on the fold line are shared.
Mesh folded_plate(double a, double b, double w, int n, int m) {
    Mesh mesh;
    std::vector<std::vector<int>> id;
    for (int i = 0; i <= 2 * n; ++i) {
        const Vec3 p = i <= n ? Vec3(0, 0, a * i / n) : Vec3(b * (i - n) / n, 0, a);
        id.emplace_back();
        for (int k = 0; k <= m; ++k) id.back().push_back(mesh.add_node(p + Vec3(0, w * k / m, 0)));
    }
    ElementBlock blk{"fold", ElementShape::Quad4, {}};
    for (int i = 0; i < 2 * n; ++i)
        for (int k = 0; k < m; ++k) {
            const int q[4] = {id[i][k], id[i + 1][k], id[i + 1][k + 1], id[i][k + 1]};
            blk.add(q);
        }
    mesh.blocks.push_back(blk);
    return mesh;
}
}  // namespace

TEST(Mitc4Modal, SparseAssemblyMatchesTheDenseOne) {
    // Cantilever strip 0.5 x 0.05 x 0.002, 20 x 2 elements: lowest 4 modes from lib/modal vs the dense
    // generalized eigensolver of the test assembly. Same element matrices; the stiffness spans about
    // 11 decades (membrane against thin-plate bending), which leaves ~1e-7 of round-off on the lowest
    // frequency in either solver (first guess 1e-8 was too tight: measured 1.0e-7): allowed 1e-6.
    const double L = 0.5, b = 0.05, t = 0.002;
    Mesh mesh = rectangle_quads(L, b, 20, 2);
    Model model(mesh);
    model.add_block(0, 6, mitc4_kernel(t));
    model.fix_node_set("x0");
    const auto r = modal::solve_modes(model.assemble(), {.modes = 4});

    auto dense = shelltest::grid(L, b, 20, 2);
    dense.assemble(t, kShellSteel);
    std::vector<bool> fixed(dense.dofs(), false);
    for (int k = 0; k < static_cast<int>(dense.nodes.size()); ++k)
        if (dense.nodes[k].x() < 1e-12)
            for (int d = 0; d < 6; ++d) fixed[6 * k + d] = true;
    const Eigen::VectorXd w = shelltest::natural_frequencies(dense.K, dense.M, shelltest::Partition(fixed), 4);
    for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(r.frequencies_hz(k), w[k] / (2 * std::numbers::pi), 1e-6 * r.frequencies_hz(k)) << "mode " << k + 1;
}

TEST(Mitc4Modal, FreeFlatAndFoldedPlatesHaveExactlySixRigidModes) {
    // Free-free (negative shift admits the rigid modes): six near-zero frequencies, then elastic ones
    // far above. Without a drilling stiffness every flat node would add a zero-energy rotation.
    for (bool folded : {false, true}) {
        for (bool lumped : {false, true}) {
            Mesh mesh = folded ? folded_plate(0.3, 0.4, 0.1, 12, 4) : rectangle_quads(0.4, 0.3, 8, 6);
            Model model(mesh);
            model.add_block(0, 6, mitc4_kernel(0.003, lumped));
            const auto r = modal::solve_modes(model.assemble(), {.modes = 8, .shift_hz = -5.0});
            const double first_elastic = r.frequencies_hz(6);
            EXPECT_GT(first_elastic, 1.0) << (folded ? "folded" : "flat");
            for (int k = 0; k < 6; ++k)
                EXPECT_LT(std::abs(r.frequencies_hz(k)), 1e-3 * first_elastic)
                    << (folded ? "folded" : "flat") << (lumped ? ", lumped" : "") << " mode " << k + 1;
        }
    }
}

TEST(Mitc4Modal, ScrewsAsCoupledTranslationsJoinTwoPlates) {
    // Two 0.2 x 0.05 strips lapped over 0.05 m (the second 3 mm above the first) and joined by three
    // coupled node pairs (a screw each), clamped at the lower strip's root: a 0.35 m cantilever.
    const double t = 0.003, w = 0.05;
    Mesh a = rectangle_quads(0.2, w, 20, 4, ElementShape::Quad4, "lower");
    Mesh b = rectangle_quads(0.2, w, 20, 4, ElementShape::Quad4, "upper");
    b.translate(Vec3(0.15, 0, t));
    const int offset = a.node_count();
    const std::vector<int> clamped = a.node_set("x0");  // before append merges the upper strip's "x0"
    a.append(b);
    Model model(a);
    model.add_block(0, 6, mitc4_kernel(t));
    model.add_block(1, 6, mitc4_kernel(t));
    model.fix_nodes(clamped);
    // Three screws, not on one line: with coupled translations only, two screws would leave the
    // upper strip free to turn about the line through them (a hinge, a rigid-body mode). Lower node
    // (i along, j across) is 21 j + i; the upper strip starts at i = 15.
    auto lower = [](int i, int j) { return 21 * j + i; };
    for (auto [i, j] : {std::pair{16, 1}, std::pair{16, 3}, std::pair{19, 2}})
        model.couple({lower(i, j), offset + lower(i - 15, j)}, kTranslations);
    const auto joined = modal::solve_modes(model.assemble(), {.modes = 1});

    Mesh single = rectangle_quads(0.2, w, 20, 4);
    Model m1(single);
    m1.add_block(0, 6, mitc4_kernel(t));
    m1.fix_node_set("x0");
    const auto alone = modal::solve_modes(m1.assemble(), {.modes = 1});
    // The joined pair is longer (0.35 m): its first bending frequency must be well below the 0.2 m
    // strip's (by about (0.2/0.35)^2 = 0.33 for a uniform beam; the lap makes it a bit stiffer).
    EXPECT_LT(joined.frequencies_hz(0), 0.6 * alone.frequencies_hz(0));
    EXPECT_GT(joined.frequencies_hz(0), 0.2 * alone.frequencies_hz(0));
}
