// mesh/mesh_tools.hpp: the graded quad4 grid (and parallelogram_quad4 as its uniform case), welding
// coincident nodes, the nearest node among candidates; values worked out by hand. The reverse
// Cuthill-McKee renumbering on a path worked out by hand and on tet10 blocks numbered as Gmsh does.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "core/error.hpp"
#include "mesh/mesh.hpp"
#include "mesh/mesh_tools.hpp"

using namespace fem;

TEST(MeshTools, GradedGridNodesNumberingAndOrientation) {
    const std::vector<double> a = {0.0, 0.1, 0.3}, b = {-1.0, 0.0, 0.5, 2.0};
    const Vec3 origin(1, 2, 3), u(0, 0, -1), v(0, 1, 0);
    const Mesh m = graded_parallelogram_quad4(origin, u, v, a, b, "plate");
    ASSERT_EQ(m.node_count(), 12);
    ASSERT_EQ(m.blocks.size(), 1u);
    EXPECT_EQ(m.blocks[0].part, "plate");
    EXPECT_EQ(m.blocks[0].size(), 6);
    EXPECT_EQ(m.nodes[2 * 3 + 1], Vec3(1, 2.5, 2.9));  // node (i, j) = (1, 2): origin + 0.1 u + 0.5 v
    // Every element counter-clockwise about u x v = (1, 0, 0): positive area seen along it.
    for (int e = 0; e < 6; ++e) {
        const auto x = m.element_coordinates(0, e);
        EXPECT_GT((x[1] - x[0]).cross(x[2] - x[1]).dot(u.cross(v)), 0.0) << e;
    }
    const std::vector<double> flat = {0.0, 0.0, 1.0};
    EXPECT_THROW(graded_parallelogram_quad4(origin, u, v, flat, b, "plate"), InputError);
    EXPECT_THROW(graded_parallelogram_quad4(origin, u, u, a, b, "plate"), InputError);
}

TEST(MeshTools, UniformGridIsParallelogramQuad4BitForBit) {
    const Vec3 c(0.3, -0.2, 0.1), u(0.7, 0.1, 0), v(-0.05, 0.4, 0.2);
    const Mesh p = parallelogram_quad4(c, u, v, 5, 3, "plate");
    std::vector<double> a, b;
    for (int i = 0; i <= 5; ++i) a.push_back(static_cast<double>(i) / 5 - 0.5);
    for (int j = 0; j <= 3; ++j) b.push_back(static_cast<double>(j) / 3 - 0.5);
    const Mesh g = graded_parallelogram_quad4(c, u, v, a, b, "plate");
    ASSERT_EQ(p.node_count(), g.node_count());
    for (int n = 0; n < p.node_count(); ++n) EXPECT_TRUE(p.nodes[n] == g.nodes[n]) << n;
    EXPECT_EQ(p.blocks[0].connectivity, g.blocks[0].connectivity);
    // The hand-numbered layout of mesh.hpp: node (i, j) = c + (i/nu - 1/2) u + (j/nv - 1/2) v is node j (nu + 1) + i.
    EXPECT_TRUE(p.nodes[2 * 6 + 4] == c + (4.0 / 5 - 0.5) * u + (2.0 / 3 - 0.5) * v);
}

TEST(MeshTools, WeldMergesSharedRowsAndRenumbers) {
    // Two 2 x 1 strips sharing the row at y = 1: 6 + 6 nodes, 3 shared.
    const std::vector<double> x = {0.0, 1.0, 2.0}, y1 = {0.0, 1.0}, y2 = {1.0, 2.0};
    Mesh m = graded_parallelogram_quad4(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), x, y1, "lower");
    m.append(graded_parallelogram_quad4(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), x, y2, "upper"));
    m.node_sets["top of lower"] = {3, 4, 5};
    m.node_sets["bottom of upper"] = {6, 7, 8, 6};
    EXPECT_EQ(weld_coincident_nodes(m, 1e-9), 3);
    ASSERT_EQ(m.node_count(), 9);
    EXPECT_EQ(m.nodes[8], Vec3(2, 2, 0));                         // kept nodes keep their order
    EXPECT_EQ(m.blocks[1].element(0)[0], 3);                      // the upper strip's first node is the lower's node 3
    EXPECT_EQ(m.node_sets["bottom of upper"], (std::vector<int>{3, 4, 5}));  // duplicates removed
    EXPECT_EQ(m.node_sets["top of lower"], (std::vector<int>{3, 4, 5}));
    validate(m);
    EXPECT_THROW(weld_coincident_nodes(m, 0.0), InputError);
}

TEST(MeshTools, NearestNodeAmongCandidates) {
    const std::vector<double> x = {0.0, 1.0, 2.0}, y = {0.0, 1.0};
    const Mesh m = graded_parallelogram_quad4(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), x, y, "plate");
    EXPECT_EQ(nearest_node(m, Vec3(1.9, 0.8, 0.3)), 5);
    const std::vector<int> left = {0, 3};
    EXPECT_EQ(nearest_node(m, Vec3(1.9, 0.8, 0.3), left), 3);
    EXPECT_EQ(nearest_node(m, Vec3(0.5, 0.0, 0.0)), 0);  // equally near 0 and 1: the first
    EXPECT_THROW(nearest_node(m, Vec3::Zero(), std::vector<int>{}), InputError);
}

namespace {
// The mesh numbered as Gmsh numbers a second-order mesh: the corner nodes first (in their order),
// then the mid-edge nodes.
Mesh corners_first(const Mesh& m) {
    std::vector<char> corner(m.node_count(), 0);
    for (const ElementBlock& b : m.blocks)
        for (int e = 0; e < b.size(); ++e)
            for (int a = 0; a < 4; ++a) corner[b.element(e)[a]] = 1;
    std::vector<int> order(m.node_count());
    std::iota(order.begin(), order.end(), 0);
    std::stable_partition(order.begin(), order.end(), [&](int i) { return corner[i] != 0; });
    Mesh g = m;
    renumber_nodes(g, order);
    return g;
}
}  // namespace

TEST(MeshTools, ReverseCuthillMcKeeOnAPath) {
    // A chain of line elements numbered 0 - 3 - 1 - 4 - 2 along x, and a lone node 5 (no element).
    Mesh m;
    for (double x : {0.0, 2.0, 4.0, 1.0, 3.0, 9.0}) m.add_node(Vec3(x, 0, 0));
    ElementBlock line{"wire", ElementShape::Beam2, {0, 3, 3, 1, 1, 4, 4, 2}};
    m.blocks.push_back(line);
    m.node_sets["ends"] = {2, 0};
    EXPECT_EQ(node_bandwidth(m), 3);
    // Both ends have degree 1 (a pseudo-peripheral pair): the search starts at node 0 (least degree,
    // smaller number), finds the far end 2, whose level structure is no deeper, and keeps 0; the
    // Cuthill-McKee order 0 3 1 4 2 reversed; the lone node is a part of its own, after it.
    const std::vector<int> order = reverse_cuthill_mckee(m);
    EXPECT_EQ(order, (std::vector<int>{2, 4, 1, 3, 0, 5}));
    renumber_nodes(m, order);
    for (int k = 0; k < 5; ++k) EXPECT_EQ(m.nodes[k].x(), 4.0 - k) << k;
    EXPECT_EQ(m.nodes[5].x(), 9.0);
    EXPECT_EQ(node_bandwidth(m), 1);
    EXPECT_EQ(m.blocks[0].connectivity, (std::vector<int>{4, 3, 3, 2, 2, 1, 1, 0}));
    EXPECT_EQ(m.node_sets["ends"], (std::vector<int>{0, 4}));  // the set keeps its order: node 2, then node 0
    EXPECT_THROW(renumber_nodes(m, std::vector<int>{0, 1, 2}), InputError);            // too short
    EXPECT_THROW(renumber_nodes(m, std::vector<int>{0, 1, 2, 3, 4, 4}), InputError);   // repeats node 4
    EXPECT_THROW(renumber_nodes(m, std::vector<int>{0, 1, 2, 3, 4, 6}), InputError);   // no node 6
}

TEST(MeshTools, RenumberedTet10BlocksKeepTheirElementsAndSets) {
    // Two tet10 blocks in two parts, numbered corners first as Gmsh numbers them, and a third block
    // not connected to them (its own part of the graph).
    Mesh a = box_tets(1.0, 1.0, 1.0, 4, 4, 4, ElementShape::Tet10, "a");
    Mesh b = box_tets(1.0, 1.0, 1.0, 3, 3, 3, ElementShape::Tet10, "b");
    b.translate(Vec3(5, 0, 0));
    a.append(b);
    const Mesh before = corners_first(a);
    Mesh m = before;
    const std::vector<int> order = reverse_cuthill_mckee(m);
    std::vector<int> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (int i = 0; i < m.node_count(); ++i) ASSERT_EQ(sorted[i], i);
    EXPECT_EQ(reverse_cuthill_mckee(m), order);  // deterministic
    renumber_nodes(m, order);
    validate(m);
    // Every element has the same coordinates in the same node order; every set the same points.
    ASSERT_EQ(m.blocks.size(), before.blocks.size());
    for (std::size_t bi = 0; bi < m.blocks.size(); ++bi) {
        EXPECT_EQ(m.blocks[bi].part, before.blocks[bi].part);
        ASSERT_EQ(m.blocks[bi].size(), before.blocks[bi].size());
        for (int e = 0; e < m.blocks[bi].size(); ++e)
            EXPECT_EQ(m.element_coordinates(static_cast<int>(bi), e), before.element_coordinates(static_cast<int>(bi), e));
    }
    for (const auto& [name, ids] : before.node_sets) {
        ASSERT_EQ(m.node_set(name).size(), ids.size()) << name;
        for (std::size_t k = 0; k < ids.size(); ++k) EXPECT_EQ(m.nodes[m.node_set(name)[k]], before.nodes[ids[k]]) << name;
    }
    // The first block's nodes come first (its part holds node 0), each part numbered contiguously.
    int last_of_a = 0, first_of_b = m.node_count();
    for (int n : m.blocks[0].connectivity) last_of_a = std::max(last_of_a, n);
    for (int n : m.blocks[1].connectivity) first_of_b = std::min(first_of_b, n);
    EXPECT_LT(last_of_a, first_of_b);
    // The point of it: corners first, an element's nodes lie about half the mesh apart; after RCM
    // within a few layers of the grid (a 4 x 4 layer of cells has 9 x 9 = 81 nodes of the tet10 grid).
    const int width_before = node_bandwidth(before), width_after = node_bandwidth(m);
    RecordProperty("bandwidth_corners_first", width_before);
    RecordProperty("bandwidth_rcm", width_after);
    EXPECT_GT(width_before, 200);
    EXPECT_LT(width_after, 4 * 81);
    EXPECT_LT(width_after, width_before / 2);
}

// A mirror image keeps its solids right-handed: a tet10 box, a hex8 box and a quad4 plate mirrored
// through a skew plane pass validate() (positive Jacobian at every element's centre), their volumes
// are kept, a quad's normal is the mirror of the old one, and mirroring twice gives the mesh back.
TEST(MeshTools, ReflectKeepsSolidsPositiveAndMirrorsNormals) {
    const Vec3 point(0.01, -0.02, 0.184), normal(0.2, 0.1, 1.0);
    const Vec3 n = normal.normalized();
    auto volume = [](const Mesh& m) {
        double v = 0.0;
        for (const auto& b : m.blocks)
            for (int e = 0; e < b.size(); ++e) {
                const auto x = m.element_coordinates(static_cast<int>(&b - m.blocks.data()), e);
                if (b.shape == ElementShape::Tet10 || b.shape == ElementShape::Tet4) v += (x[1] - x[0]).cross(x[2] - x[0]).dot(x[3] - x[0]) / 6.0;
            }
        return v;
    };
    for (const ElementShape shape : {ElementShape::Tet10, ElementShape::Tet4}) {
        Mesh m = box_tets(0.03, 0.02, 0.01, 3, 2, 2, shape);
        const Mesh before = m;
        reflect(m, point, normal);
        EXPECT_NO_THROW(validate(m));
        EXPECT_NEAR(volume(m), 0.03 * 0.02 * 0.01, 1e-15);
        EXPECT_NEAR(volume(before), volume(m), 1e-15);
        for (int i = 0; i < m.node_count(); ++i)  // each node is the mirror image of its old position
            EXPECT_NEAR(((m.nodes[i] + before.nodes[i]) / 2 - point).dot(n), 0.0, 1e-15);
        reflect(m, point, normal);
        for (int i = 0; i < m.node_count(); ++i) EXPECT_NEAR((m.nodes[i] - before.nodes[i]).norm(), 0.0, 1e-15);
        EXPECT_EQ(m.blocks[0].connectivity, before.blocks[0].connectivity);
        EXPECT_EQ(m.node_sets, before.node_sets);
    }
    Mesh hex = box_hex8(0.03, 0.02, 0.01, 3, 2, 1);
    reflect(hex, point, normal);
    EXPECT_NO_THROW(validate(hex));

    Mesh plate = rectangle_quads(0.02, 0.01, 2, 1);  // normal +z as numbered
    auto quad_normal = [](const Mesh& m) {
        const auto x = m.element_coordinates(0, 0);
        return Vec3((x[2] - x[0]).cross(x[3] - x[1]).normalized());
    };
    const Vec3 n0 = quad_normal(plate);
    reflect(plate, point, normal);
    EXPECT_NEAR((quad_normal(plate) - (n0 - 2 * n0.dot(n) * n)).norm(), 0.0, 1e-12);

    Mesh hex20 = box_hex20(0.01, 0.01, 0.01, 1, 1, 1);
    EXPECT_THROW(reflect(hex20, point, normal), InputError);
    EXPECT_THROW(reflect(plate, point, Vec3::Zero()), InputError);
}
