// The finger meshes of Sec 3.3 (Table 3-1 geometry): volumes against the exact elliptic cylinder,
// element shape, node sets, and the time step against Table 3-2's Case A.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "element/critical_time_step.hpp"
#include "mesh/finger.hpp"

using namespace fem;
using namespace fem::finger;
using fem::units::mm;

namespace {

using std::numbers::pi;
const ElasticMaterial kRubber = fem::finger::rubber();

// The smallest element critical time step of the mesh (Table 2-1, no bulk-viscosity term: the
// undeformed mesh), as the explicit solver would compute it before the first cycle.
double min_time_step(const Mesh& m) {
    double dt = INFINITY;
    for (int b = 0; b < static_cast<int>(m.blocks.size()); ++b)
        for (int e = 0; e < m.blocks[b].size(); ++e)
            dt = std::min(dt, cfl::critical_time_step(m.blocks[b].shape, m.element_coordinates(b, e), kRubber));
    return dt;
}

// Ramanujan's perimeter of the ellipse (error ~1e-10 relative at b/a = 0.7).
double perimeter(double a, double b) { return pi * (3 * (a + b) - std::sqrt((3 * a + b) * (a + 3 * b))); }

// The polygon through M boundary nodes at equal arc spacing s = P/M misses, to leading order, the
// area sum over chords of kappa s^3 / 12 = (s^2 / 12) * integral of kappa ds = pi s^2 / 6.
double predicted_hex_volume(const EllipticCylinder& g, int boundary_nodes) {
    const double s = perimeter(g.a, g.b) / boundary_nodes;
    return (pi * g.a * g.b - pi * s * s / 6.0) * g.length;
}

void expect_node_sets(const Mesh& m, double length) {
    ASSERT_FALSE(m.node_set("root").empty());
    ASSERT_FALSE(m.node_set("tip").empty());
    for (int n : m.node_set("root")) EXPECT_NEAR(m.nodes[n].z(), 0.0, 1e-12);
    for (int n : m.node_set("tip")) EXPECT_NEAR(m.nodes[n].z(), length, 1e-12);
    // Every node on z = 0 / z = L is in the set.
    EXPECT_EQ(m.node_set("root").size(), m.select_nodes([](const Vec3& x) { return std::abs(x.z()) < 1e-12; }).size());
    EXPECT_EQ(m.node_set("tip").size(),
              m.select_nodes([&](const Vec3& x) { return std::abs(x.z() - length) < 1e-12; }).size());
    ASSERT_EQ(m.node_set("tip_center").size(), 1u);
    const int c = m.node_set("tip_center")[0];
    EXPECT_NEAR(m.nodes[c].z(), length, 1e-12);
}

}  // namespace

TEST(HexFinger, VolumeShapeAndNodeSets) {
    const EllipticCylinder g;  // Table 3-1, 4.5 inch
    for (double h : {4.0 * mm, 3.0 * mm, 2.0 * mm}) {
        SCOPED_TRACE("h = " + std::to_string(h));
        const HexCrossSection c = choose_hex_cross_section(g, h);
        const Mesh m = hex_finger(g, h);
        ASSERT_NO_THROW(validate(m));
        const int layers = static_cast<int>(std::lround(g.length / h));
        const int per_section = c.nx * c.ny + 2 * (c.nx + c.ny) * c.nr;
        EXPECT_EQ(m.element_count(), per_section * layers);
        // The layout's promise: within [0.8, 1.25] of the pi a b / h^2 elements per section.
        EXPECT_GE(per_section, 0.8 * pi * g.a * g.b / (h * h));
        EXPECT_LE(per_section, 1.25 * pi * g.a * g.b / (h * h));
        const auto q = mesh_quality(m);
        // Inscribed polygon: below pi a b L, and the chord deficit as predicted to within 10 % of
        // itself (the next term is (kappa s)^2 / 20 ~ 3 % of it at kappa s < 0.8, plus the curvature
        // variation along a chord).
        const double exact = pi * g.a * g.b * g.length, predicted = predicted_hex_volume(g, 2 * (c.nx + c.ny));
        EXPECT_LT(q.volume, exact);
        EXPECT_NEAR(q.volume, predicted, 0.1 * (exact - predicted));
        EXPECT_GE(q.min_scaled_jacobian, 0.5);  // corner angles within 30..150 degrees: no bad element
        expect_node_sets(m, g.length);
        EXPECT_EQ(m.node_set("root").size() * (layers + 1), static_cast<std::size_t>(m.node_count()));
        // The tip-centre node lies within one element of the axis.
        EXPECT_LT(m.nodes[m.node_set("tip_center")[0]].head<2>().norm(), h);
    }
}

// MeshQuality's characteristic length is Table 2-1's, as fem::cfl computes it (the solver's).
TEST(MeshQuality, CharacteristicLengthAgreesWithTable21) {
    const EllipticCylinder g;
    for (const Mesh& m : {hex_finger(g, 4.0 * mm), hex_finger(g, mapped_cross_section(5), 29), tet_finger(g, {6.0 * mm, 2})}) {
        double shortest = INFINITY;
        for (int b = 0; b < static_cast<int>(m.blocks.size()); ++b)
            for (int e = 0; e < m.blocks[b].size(); ++e)
                shortest = std::min(shortest, cfl::characteristic_length(m.blocks[b].shape, m.element_coordinates(b, e)));
        const auto q = mesh_quality(m);
        EXPECT_NEAR(q.min_characteristic_length, shortest, 1e-12 * shortest);
        const int b = q.shortest_block, e = q.shortest_element;
        EXPECT_NEAR(cfl::characteristic_length(m.blocks[b].shape, m.element_coordinates(b, e)), shortest, 1e-12 * shortest);
    }
}

// Table 3-2's counts follow from a mapped n x n cross-section: Case A 1080 nodes / 725 elements
// (5 x 5, 29 layers), Case B 5900 / 4698 (9 x 9, 58 layers). The single mapped block has corners on
// the smooth boundary; the O-grid avoids them.
TEST(HexFinger, MappedReconstructionOfCasesAAndB) {
    const EllipticCylinder g;
    const Mesh a = hex_finger(g, mapped_cross_section(5), 29);
    const Mesh b = hex_finger(g, mapped_cross_section(9), 58);
    EXPECT_EQ(a.node_count(), 1080);
    EXPECT_EQ(a.element_count(), 725);
    EXPECT_EQ(b.node_count(), 5900);
    EXPECT_EQ(b.element_count(), 4698);
    ASSERT_NO_THROW(validate(a));
    ASSERT_NO_THROW(validate(b));
    const double exact = pi * g.a * g.b * g.length;
    for (const auto& [mesh, n] : {std::pair{&a, 5}, std::pair{&b, 9}}) {
        const auto q = mesh_quality(*mesh);
        const double predicted = predicted_hex_volume(g, 4 * n);
        EXPECT_NEAR(q.volume, predicted, 0.1 * (exact - predicted));
    }
    EXPECT_LT(mesh_quality(a).min_scaled_jacobian, mesh_quality(hex_finger(g, 4.0 * mm)).min_scaled_jacobian);
    // Thesis trend: the refined mesh needs the smaller step.
    EXPECT_GT(min_time_step(a), min_time_step(b));
}

// Table 3-2, Case A: hexahedra of 4 mm, numerical time step 4.04 us. Our O-grid at the same element
// size must allow a larger step than the thesis's mesh and than our mapped reconstruction of it.
TEST(HexFinger, TimeStepBeatsCaseA) {
    const EllipticCylinder g;
    const Mesh ours = hex_finger(g, 4.0 * mm);
    const Mesh mapped = hex_finger(g, mapped_cross_section(5), 29);
    const double dt = min_time_step(ours);
    EXPECT_GT(dt, 4.04e-6);
    EXPECT_GT(0.9 * dt, 4.04e-6);  // even if the thesis's value already includes LS-DYNA's 0.9 factor
    EXPECT_GT(dt, min_time_step(mapped));
    // Case B (2 mm, thesis 1.43 us) likewise.
    EXPECT_GT(0.9 * min_time_step(hex_finger(g, 2.0 * mm)), 1.43e-6);
}

TEST(HexFinger, BadInput) {
    const EllipticCylinder g;
    EXPECT_THROW(hex_finger(g, HexCrossSection{0, 2, 1, 0.5, 0.5, 0.0}, 10), InputError);
    EXPECT_THROW(hex_finger(g, HexCrossSection{4, 2, 0, 0.5, 0.5, 0.0}, 10), InputError);  // ring-less block inside
    EXPECT_THROW(hex_finger(g, HexCrossSection{4, 2, 1, 1.0, 0.5, 0.0}, 10), InputError);  // ring of zero width
    EXPECT_THROW(hex_finger(g, HexCrossSection{}, 0), InputError);
    EXPECT_THROW(hex_finger(EllipticCylinder{12 * mm, -1.0, 0.1}, 4 * mm), InputError);
    EXPECT_THROW(hex_finger(g, -1.0), InputError);
    EXPECT_THROW(mapped_cross_section(0), InputError);
}

TEST(TetFinger, LinearAndQuadratic) {
    const EllipticCylinder g;
    const double exact = pi * g.a * g.b * g.length;
    const Mesh t4 = tet_finger(g, {6.0 * mm, 1});
    const Mesh t10 = tet_finger(g, {6.0 * mm, 2});
    ASSERT_NO_THROW(validate(t4));
    ASSERT_NO_THROW(validate(t10));
    EXPECT_EQ(t4.blocks.at(0).shape, ElementShape::Tet4);
    EXPECT_EQ(t10.blocks.at(0).shape, ElementShape::Tet10);
    EXPECT_EQ(t4.element_count(), t10.element_count());  // setOrder(2) only adds nodes
    EXPECT_EQ(t4.blocks.size(), 1u);                      // root and tip faces are node sets, not blocks
    // Linear: an inscribed polyhedron, below the exact volume by at most the chord deficit of the
    // longest edge (pi s^2 / 6 per unit length, see the hex test).
    const auto q4 = mesh_quality(t4);
    EXPECT_LT(q4.volume, exact);
    EXPECT_GT(q4.volume, exact - pi * q4.max_edge * q4.max_edge / 6.0 * g.length);
    // Quadratic: mid-edge nodes on the ellipse; the boundary error drops to O((kappa s)^4): 1e-3.
    const auto q10 = mesh_quality(t10);
    EXPECT_NEAR(q10.volume, exact, 1e-3 * exact);
    EXPECT_GT(q10.min_jacobian_ratio, 0.0);  // no curved element folds over
    EXPECT_GT(q4.min_scaled_jacobian, 0.0);
    // Mid-edge nodes sit on their edges (interior ones exactly, boundary ones moved onto the curved
    // surface by the sagitta s^2 kappa / 8, kappa <= a / b^2 the ellipse's largest curvature; x1.5
    // because Gmsh takes the parametric, not the arc-length, midpoint of the curve, which adds a
    // tangential offset of the same order). A wrong node order would miss by ~ s / 2.
    const double kappa_max = g.a / (g.b * g.b);
    const int edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}};
    for (int e = 0; e < t10.blocks[0].size(); ++e) {
        const auto x = t10.element_coordinates(0, e);
        for (int k = 0; k < 6; ++k) {
            const Vec3 a = x[edge[k][0]], b = x[edge[k][1]];
            const double s = (b - a).norm();
            ASSERT_LT((x[4 + k] - 0.5 * (a + b)).norm(), 1.5 * s * s * kappa_max / 8.0) << "element " << e << " node " << 4 + k;
        }
    }
    expect_node_sets(t4, g.length);
    expect_node_sets(t10, g.length);
    // The tip centre is a mesh node (embedded point) exactly on the axis.
    EXPECT_LT(t10.nodes[t10.node_set("tip_center")[0]].head<2>().norm(), 1e-12);
    EXPECT_THROW(tet_finger(g, {6.0 * mm, 3}), InputError);
    EXPECT_THROW(tet_finger(g, {-1.0, 1}), InputError);
}

// "Average element length" read as the regular tetrahedron of mean element volume (TetOptions).
TEST(TetFinger, MeanElementSizeMatchesTarget) {
    const EllipticCylinder g;
    const double h = 5.0 * mm;
    const Mesh m = tet_finger(g, {h, 1});
    const double mean_volume = mesh_quality(m).volume / m.element_count();
    const double h_mean = std::cbrt(6.0 * std::sqrt(2.0) * mean_volume);
    EXPECT_NEAR(h_mean, h, 0.1 * h);  // one proportional correction of Gmsh's size: within 10 %
}

// Observation 1 of Sec 3.3: at the same element length tetrahedra need a smaller step than hexahedra.
TEST(TetFinger, TetrahedraNeedSmallerStepThanHexahedra) {
    const EllipticCylinder g;
    EXPECT_LT(min_time_step(tet_finger(g, {4.0 * mm, 2})), min_time_step(hex_finger(g, 4.0 * mm)));
}

TEST(DetailedFinger, GeometryAndMesh) {
    DetailedFinger d;  // the reconstruction's defaults on the 4.5-inch finger
    const double exact = detailed_finger_volume(d);
    const double body = pi * d.body.a * d.body.b * d.body.length;
    EXPECT_GT(exact, body);  // the taper and the ribs add material
    const Mesh m = detailed_finger(d, {5.0 * mm, 2});
    ASSERT_NO_THROW(validate(m));
    const auto q = mesh_quality(m);
    EXPECT_NEAR(q.volume, exact, 1e-3 * exact);  // quadratic boundary, as for the plain cylinder
    EXPECT_GT(q.min_jacobian_ratio, 0.0);
    expect_node_sets(m, d.body.length);
    // The root face is the enlarged ellipse: it reaches x = root_scale * a.
    double reach = 0.0;
    for (int n : m.node_set("root")) reach = std::max(reach, m.nodes[n].x());
    EXPECT_NEAR(reach, d.root_scale * d.body.a, 1e-9);
    // Ribs reach a + rib_height somewhere along the body.
    double rib = 0.0;
    for (const auto& x : m.nodes)
        if (x.z() > d.taper_length) rib = std::max(rib, x.x());
    EXPECT_NEAR(rib, d.body.a + d.rib_height, 1e-9);

    DetailedFinger pocket = d;
    pocket.magnet_pocket = true;
    pocket.rib_count = 0;
    const Mesh p = detailed_finger(pocket, {6.0 * mm, 1});
    ASSERT_NO_THROW(validate(p));
    const auto qp = mesh_quality(p);
    EXPECT_LT(qp.volume, detailed_finger_volume(pocket));  // inscribed, linear
    EXPECT_GT(qp.volume, detailed_finger_volume(pocket) - pi * qp.max_edge * qp.max_edge / 6.0 * d.body.length);

    DetailedFinger bad = d;
    bad.root_scale = 0.9;
    EXPECT_THROW(detailed_finger(bad, {5.0 * mm, 1}), InputError);
}

TEST(Table32, CaseDefinitions) {
    const auto cases = table_3_2_cases();
    ASSERT_EQ(cases.size(), 4u);
    EXPECT_EQ(cases[0].id, "A");
    EXPECT_EQ(cases[0].shape, ElementShape::Hex8);
    EXPECT_DOUBLE_EQ(cases[1].element_length, 2.0 * mm);
    EXPECT_EQ(cases[2].shape, ElementShape::Tet10);
    EXPECT_TRUE(cases[3].detailed);
    EXPECT_DOUBLE_EQ(cases[3].element_length, 2.8 * mm);
    for (const auto& c : cases) EXPECT_DOUBLE_EQ(c.finger_length, 4.5 * units::inch);
    const Mesh a = mesh_case(cases[0]);
    EXPECT_EQ(a.element_count(), hex_finger(EllipticCylinder{}, 4.0 * mm).element_count());
}
