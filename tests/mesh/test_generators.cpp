// The structured generators of mesh/mesh.hpp: counts, sizes and node sets worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "mesh/finger.hpp"
#include "mesh/mesh.hpp"

using namespace fem;

namespace {
// Area of a planar quadrilateral from its corner nodes (shoelace formula in the z = 0 plane).
double corner_area(const Mesh& m, int block, int e) {
    const auto x = m.element_coordinates(block, e);
    double A = 0.0;
    for (int i = 0; i < 4; ++i) A += x[i].x() * x[(i + 1) % 4].y() - x[(i + 1) % 4].x() * x[i].y();
    return 0.5 * A;
}
}  // namespace

TEST(BoxHex8, CountsVolumeAndFaces) {
    const Mesh m = box_hex8(2.0, 3.0, 5.0, 2, 3, 4);
    EXPECT_EQ(m.node_count(), 3 * 4 * 5);
    EXPECT_EQ(m.element_count(), 2 * 3 * 4);
    EXPECT_NO_THROW(validate(m));
    const auto q = finger::mesh_quality(m);
    EXPECT_NEAR(q.volume, 30.0, 1e-12);               // the box's volume
    EXPECT_NEAR(q.min_scaled_jacobian, 1.0, 1e-12);   // right-angled bricks
    EXPECT_EQ(m.node_set("x0").size(), 4u * 5u);      // (ny+1)(nz+1) nodes on each x face
    EXPECT_EQ(m.node_set("z1").size(), 3u * 4u);
    for (int n : m.node_set("y1")) EXPECT_DOUBLE_EQ(m.nodes[n].y(), 3.0);
    EXPECT_THROW(box_hex8(1, 1, 1, 0, 1, 1), InputError);
}

TEST(RectangleQuads, Quad4CountsAndArea) {
    const Mesh m = rectangle_quads(4.0, 2.0, 4, 2);
    EXPECT_EQ(m.node_count(), 5 * 3);
    EXPECT_EQ(m.element_count(), 8);
    double area = 0.0;
    for (int e = 0; e < m.blocks[0].size(); ++e) {
        const double A = corner_area(m, 0, e);
        EXPECT_GT(A, 0.0) << "element " << e << " is clockwise";
        area += A;
    }
    EXPECT_NEAR(area, 8.0, 1e-12);
    EXPECT_EQ(m.node_set("x1").size(), 3u);
    EXPECT_EQ(m.node_set("y0").size(), 5u);
}

TEST(RectangleQuads, Quad8SerendipityNodesAreEdgeMidpoints) {
    const int nx = 3, ny = 2;
    const Mesh m = rectangle_quads(3.0, 2.0, nx, ny, ElementShape::Quad8);
    // (2nx+1)(2ny+1) half-spacing grid points minus the nx*ny element centres.
    EXPECT_EQ(m.node_count(), (2 * nx + 1) * (2 * ny + 1) - nx * ny);
    EXPECT_EQ(m.element_count(), nx * ny);
    double area = 0.0;
    for (int e = 0; e < m.blocks[0].size(); ++e) {
        const auto x = m.element_coordinates(0, e);
        area += corner_area(m, 0, e);
        // Gmsh/VTK serendipity order: mid-edge nodes 4..7 on edges 01, 12, 23, 30.
        for (int k = 0; k < 4; ++k) EXPECT_LT((x[4 + k] - 0.5 * (x[k] + x[(k + 1) % 4])).norm(), 1e-14);
    }
    EXPECT_NEAR(area, 6.0, 1e-12);
    EXPECT_EQ(m.node_set("x0").size(), static_cast<std::size_t>(2 * ny + 1));
    EXPECT_THROW(rectangle_quads(1, 1, 1, 1, ElementShape::Tri3), InputError);
}

TEST(LineBeam2, CountsLengthAndEnds) {
    const Mesh m = line_beam2(Vec3(0, 0, 0), Vec3(3, 4, 0), 10);
    EXPECT_EQ(m.node_count(), 11);
    EXPECT_EQ(m.element_count(), 10);
    double length = 0.0;
    for (int e = 0; e < 10; ++e) {
        const auto x = m.element_coordinates(0, e);
        length += (x[1] - x[0]).norm();
    }
    EXPECT_NEAR(length, 5.0, 1e-12);
    EXPECT_EQ(m.node_set("start"), std::vector<int>{0});
    EXPECT_EQ(m.node_set("end"), std::vector<int>{10});
    EXPECT_THROW(line_beam2(Vec3(0, 0, 0), Vec3(1, 0, 0), 0), InputError);
}

TEST(Generators, RefuseCountsBeyondIntBeforeAllocating) {
    // 70000 x 70000 quad4: 4.9e9 elements would overflow the int node numbering (issue 14).
    try {
        rectangle_quads(1, 1, 70000, 70000);
        ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("a 70000 x 70000 quad4 grid has 4.9e+09 nodes"), std::string::npos) << e.what();
    }
    EXPECT_THROW(box_hex8(1, 1, 1, 2000, 2000, 2000), InputError);
    EXPECT_THROW(line_beam2(Vec3::Zero(), Vec3::UnitX(), std::numeric_limits<int>::max()), InputError);
}
