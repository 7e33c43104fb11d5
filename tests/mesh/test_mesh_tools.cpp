// mesh/mesh_tools.hpp: the graded quad4 grid (and parallelogram_quad4 as its uniform case), welding
// coincident nodes, the nearest node among candidates; values worked out by hand.
#include <gtest/gtest.h>

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
