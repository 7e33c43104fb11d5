// Unit tests of the contact kernels (thesis Sec 2.3.6-2.3.7): surfaces and Eq 2-30 stiffness,
// search vs brute force, projection, penalty force and momentum, Coulomb return mapping (stick,
// slip, Eq 2-35 decay), two-way contact, rigid motion. Every tolerance is set by the arithmetic
// (round-off) unless a comment says otherwise.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <cmath>
#include <numbers>
#include <random>
#include <set>

#include "contact/contact.hpp"
#include "io/hdf5.hpp"
#include "explicit/rigid_motion.hpp"
#include "core/error.hpp"
#include "../test_materials.hpp"

#include <fmt/format.h>

using namespace fem;
using fem::test::kSteel;
using namespace fem::contact;

namespace {
const ElasticMaterial kTable31Rubber = ElasticMaterial::make("rubber", 6.1e6, 0.49, 1000);

Vec3 segment_centre(const Segment& s, std::span<const Vec3> x) {
    Vec3 c = Vec3::Zero();
    for (int i = 0; i < s.count; ++i) c += x[s.n[i]] / s.count;
    return c;
}
Vec3 segment_normal(const Segment& s, std::span<const Vec3> x) {
    if (s.count == 3) return (x[s.n[1]] - x[s.n[0]]).cross(x[s.n[2]] - x[s.n[0]]).normalized();
    return (x[s.n[2]] - x[s.n[0]]).cross(x[s.n[3]] - x[s.n[1]]).normalized();
}

// The hex8 box split into 6 tetrahedra per hexahedron (Kuhn split along the 0-6 diagonal:
// conforming because every hexahedron of box_hex8 is numbered the same way).
Mesh box_tet4(double lx, double ly, double lz, int nx, int ny, int nz) {
    Mesh hex = box_hex8(lx, ly, lz, nx, ny, nz, "tets");
    Mesh m;
    m.nodes = hex.nodes;
    ElementBlock b{"tets", ElementShape::Tet4, {}};
    constexpr int kuhn[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
    for (int e = 0; e < hex.blocks[0].size(); ++e) {
        const auto c = hex.blocks[0].element(e);
        for (const auto& t : kuhn) {
            int tet[4] = {c[t[0]], c[t[1]], c[t[2]], c[t[3]]};
            const Vec3 &a = m.nodes[tet[0]], &bb = m.nodes[tet[1]], &cc = m.nodes[tet[2]], &d = m.nodes[tet[3]];
            if ((bb - a).dot((cc - a).cross(d - a)) < 0) std::swap(tet[1], tet[2]);
            b.add(tet);
        }
    }
    m.blocks.push_back(b);
    return m;
}
}  // namespace

// --- surfaces ----------------------------------------------------------------------------------

TEST(ContactSurface, Hex8BoxBoundaryFacesAreOutwardWithEq230Stiffness) {
    const Mesh m = box_hex8(1.0, 2.0, 3.0, 2, 3, 4, "box");
    const ContactSurface s = ContactSurface::from_part(m, "box", kTable31Rubber, 1.0);
    EXPECT_EQ(s.segments.size(), 2u * (2 * 3 + 3 * 4 + 2 * 4));
    EXPECT_EQ(s.nodes.size(), static_cast<std::size_t>(3 * 4 * 5 - 1 * 2 * 3));  // all but the interior nodes
    const Vec3 centre(0.5, 1.0, 1.5);
    double area = 0;
    const double B = kTable31Rubber.youngs_modulus / (3 * (1 - 2 * kTable31Rubber.poissons_ratio));  // Eq 2-33
    for (const auto& seg : s.segments) {
        EXPECT_EQ(seg.count, 4);
        const Vec3 n = segment_normal(seg, m.nodes), c = segment_centre(seg, m.nodes);
        // Outward: the normal points along the face's outward axis.
        const Vec3 d = c - centre;
        const Vec3 outward = (d.array().abs() / Vec3(0.5, 1.0, 1.5).array()).matrix().maxCoeff() > 0
                                 ? Vec3((std::abs(std::abs(d.x()) - 0.5) < 1e-12) * (d.x() > 0 ? 1.0 : -1.0),
                                        (std::abs(std::abs(d.y()) - 1.0) < 1e-12) * (d.y() > 0 ? 1.0 : -1.0),
                                        (std::abs(std::abs(d.z()) - 1.5) < 1e-12) * (d.z() > 0 ? 1.0 : -1.0))
                                 : Vec3::Zero();
        EXPECT_NEAR(n.dot(outward), 1.0, 1e-12);
        area += seg.area;
        const double V = 0.5 * (2.0 / 3) * 0.75;
        EXPECT_NEAR(seg.volume, V, 1e-14);
        EXPECT_NEAR(seg.stiffness, B * seg.area * seg.area / V, 1e-9 * seg.stiffness);  // Eq 2-30a
    }
    EXPECT_NEAR(area, 2 * (1 * 2 + 2 * 3 + 1 * 3), 1e-12);
}

TEST(ContactSurface, Tet4BoxHasTheSameAreaAndOutwardTriangles) {
    const Mesh m = box_tet4(1.0, 2.0, 3.0, 2, 3, 4);
    const ContactSurface s = ContactSurface::from_part(m, "tets", kSteel);
    EXPECT_EQ(s.segments.size(), 2u * 2u * (2 * 3 + 3 * 4 + 2 * 4));  // two triangles per boundary quad
    double area = 0;
    for (const auto& seg : s.segments) {
        EXPECT_EQ(seg.count, 3);
        const Vec3 c = segment_centre(seg, m.nodes);
        // Outward: stepping along the normal leaves the box.
        const Vec3 out = c + 1e-3 * segment_normal(seg, m.nodes);
        const bool inside = out.x() > 0 && out.x() < 1 && out.y() > 0 && out.y() < 2 && out.z() > 0 && out.z() < 3;
        EXPECT_FALSE(inside);
        area += seg.area;
    }
    EXPECT_NEAR(area, 22.0, 1e-12);
    EXPECT_EQ(s.nodes.size(), static_cast<std::size_t>(3 * 4 * 5 - 1 * 2 * 3));
}

TEST(ContactSurface, Tet10UsesCornerTrianglesAndKeepsMidEdgeNodesAsSlaves) {
    Mesh m;
    const Vec3 c[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const auto& p : c) m.add_node(p);
    constexpr int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}};  // Gmsh order
    for (const auto& e : edges) m.add_node(0.5 * (c[e[0]] + c[e[1]]));
    ElementBlock b{"t10", ElementShape::Tet10, {}};
    const int conn[10] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
    b.add(conn);
    m.blocks.push_back(b);
    const ContactSurface s = ContactSurface::from_part(m, "t10", kSteel);
    ASSERT_EQ(s.segments.size(), 4u);
    EXPECT_EQ(s.nodes.size(), 10u);
    double area = 0;
    for (const auto& seg : s.segments) area += seg.area;
    EXPECT_NEAR(area, 1.5 + std::sqrt(3.0) / 2, 1e-12);
}

TEST(ContactSurface, ShellStiffnessIsEq230b) {
    const Mesh m = rectangle_quads(2.0, 1.0, 2, 1, ElementShape::Quad4, "plate");
    const ContactSurface s = ContactSurface::from_part(m, "plate", kSteel, 0.5);
    ASSERT_EQ(s.segments.size(), 2u);
    const double B = kSteel.bulk_modulus();
    EXPECT_NEAR(s.segments[0].stiffness, 0.5 * B * 1.0 / std::sqrt(2.0), 1e-6 * B);
    EXPECT_THROW(ContactSurface::from_part(line_beam2(Vec3::Zero(), Vec3::UnitX(), 3, "b"), "b", kSteel), InputError);
    EXPECT_THROW(ContactSurface::from_part(m, "plate", kSteel, 0.0), InputError);
}

// --- search ------------------------------------------------------------------------------------

TEST(ContactSearch, HashGridFindsExactlyTheBruteForceBoxes) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int trial = 0; trial < 5; ++trial) {
        const int n = 2000;
        std::vector<Box> boxes(n);
        for (auto& b : boxes) {
            const Vec3 c(U(rng), U(rng), U(rng));
            // Sizes over two decades, including a few large ones.
            const double h = (U(rng) < 0.02 ? 0.3 : 0.01 + 0.05 * U(rng));
            b.lo = c - h * Vec3(U(rng), U(rng), U(rng));
            b.hi = c + h * Vec3(U(rng), U(rng), U(rng));
        }
        SpatialHashGrid grid;
        grid.build(boxes);
        std::vector<int> a, bf;
        for (int q = 0; q < 3000; ++q) {
            const Vec3 p(1.2 * U(rng) - 0.1, 1.2 * U(rng) - 0.1, 1.2 * U(rng) - 0.1);
            a.clear();
            bf.clear();
            grid.query(p, a);
            brute_force_query(boxes, p, bf);
            ASSERT_EQ(a, bf) << "trial " << trial << " query " << q;
        }
    }
}

// The Verlet candidate list under random motion: every (node, segment) pair that satisfies the
// contact criterion (behind the face by at most depth, projecting onto it within the lateral
// tolerance; computed by brute force over all pairs) must be among the candidates at every cycle,
// while the master surface translates, warps and turns and the nodes wander, and while the list
// is rebuilt far less often than every cycle.
TEST(ContactSearch, CandidateListNeverMissesAPairUnderRandomMotion) {
    const Mesh m = box_hex8(1.0, 1.0, 0.2, 10, 10, 2, "plate");
    const ContactSurface master = ContactSurface::from_part(m, "plate", kSteel);
    std::vector<Vec3> xm = m.nodes;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    std::vector<Vec3> xs(400), vel(400);
    for (std::size_t i = 0; i < xs.size(); ++i) {
        xs[i] = Vec3(0.5 + 0.6 * U(rng), 0.5 + 0.6 * U(rng), 0.1 + 0.15 * U(rng));
        vel[i] = 0.002 * Vec3(U(rng), U(rng), U(rng));
    }
    const std::size_t ns = master.segments.size();
    std::vector<double> depth(ns, 0.05), lateral(ns, 0.005);
    std::set<int> mnodes;
    for (const auto& s : master.segments)
        for (int k = 0; k < s.count; ++k) mnodes.insert(s.n[k]);
    const std::vector<int> master_nodes(mnodes.begin(), mnodes.end());
    const double turn = 1 + 2 * 0.05 / 0.1;  // depth / h with h = 0.1 (the plate's faces)
    CandidateList list(0.02, 1000);
    long pairs_checked = 0;
    for (int cycle = 0; cycle < 60; ++cycle) {
        for (std::size_t i = 0; i < xs.size(); ++i) xs[i] += vel[i];
        // Master: a drift, a growing warp, and a turn about the z axis through the plate centre.
        const double a = 0.0015 * cycle;
        const Eigen::Matrix3d R = Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix();
        for (std::size_t k = 0; k < xm.size(); ++k) {
            const Vec3& X = m.nodes[k];
            xm[k] = Vec3(0.5, 0.5, 0) + R * (X - Vec3(0.5, 0.5, 0)) +
                    Vec3(0.0005 * cycle, 0, 0.0005 * cycle * std::sin(6 * X.x()) * std::cos(5 * X.y()));
        }
        list.update(xs, xm, master.segments, depth, lateral, master_nodes, turn, [](int, int) { return false; });
        for (std::size_t i = 0; i < xs.size(); ++i) {
            const auto c = list.candidates(static_cast<int>(i));
            for (std::size_t s = 0; s < ns; ++s) {
                const auto& seg = master.segments[s];
                const Projection p = project_quad(xs[i], xm[seg.n[0]], xm[seg.n[1]], xm[seg.n[2]], xm[seg.n[3]]);
                if (p.gap < 0 && -p.gap <= depth[s] && p.tangential_offset <= lateral[s]) {
                    ++pairs_checked;
                    ASSERT_TRUE(std::find(c.begin(), c.end(), static_cast<int>(s)) != c.end())
                        << "cycle " << cycle << " node " << i << " segment " << s << " missed";
                }
            }
        }
    }
    EXPECT_GT(pairs_checked, 300);
    // Per cycle d_s + f d_m <~ 0.0035 + 2 x 0.0015 against a 0.02 margin: a rebuild every ~3 cycles.
    EXPECT_LT(list.rebuilds(), 60 / 2);
    std::printf("[ search ] %ld contact pairs verified, %ld rebuilds in %ld cycles\n", pairs_checked, list.rebuilds(),
                list.cycles());
}

// Cost proportional to surface size: the grid search of n nodes against n segments, timed for
// n and 4n (should scale ~linearly), and against brute force (n^2). Timings are printed, not
// asserted (speed belongs to benchmarks); the pair counts are asserted equal.
TEST(ContactSearch, GridSearchScalesWithSurfaceSizeAndMatchesBruteForce) {
    auto run = [](int nx, bool brute, long& pairs) {
        const Mesh m = box_hex8(1.0, 1.0, 0.1, nx, nx, 1, "p");
        const ContactSurface s = ContactSurface::from_part(m, "p", kSteel);
        std::vector<Box> boxes;
        for (const auto& seg : s.segments) {
            Box b{m.nodes[seg.n[0]], m.nodes[seg.n[0]]};
            for (int k = 1; k < 4; ++k) {
                b.lo = b.lo.cwiseMin(m.nodes[seg.n[k]]);
                b.hi = b.hi.cwiseMax(m.nodes[seg.n[k]]);
            }
            b.lo.array() -= 0.3 / nx;
            b.hi.array() += 0.3 / nx;
            boxes.push_back(b);
        }
        std::vector<Vec3> pts;
        for (int i = 0; i < nx; ++i)
            for (int j = 0; j < nx; ++j) pts.emplace_back((i + 0.37) / nx, (j + 0.61) / nx, 0.1 + 0.1 / nx);
        double best = 1e300;
        for (int rep = 0; rep < 3; ++rep) {  // the fastest of 3 (the machine is shared)
        const auto t0 = std::chrono::steady_clock::now();
        std::vector<int> out;
        pairs = 0;
        if (brute) {
            for (const auto& p : pts) {
                out.clear();
                brute_force_query(boxes, p, out);
                pairs += static_cast<long>(out.size());
            }
        } else {
            SpatialHashGrid g;
            g.build(boxes);
            for (const auto& p : pts) {
                out.clear();
                g.query(p, out);
                pairs += static_cast<long>(out.size());
            }
        }
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        }
        return std::make_pair(best, static_cast<long>(s.segments.size()));
    };
    long p1, p2, pb;
    const auto [t1, n1] = run(60, false, p1);
    const auto [t2, n2] = run(120, false, p2);
    const auto [tb, nb] = run(60, true, pb);
    EXPECT_EQ(p1, pb);
    std::printf("[ search ] grid: %ld segments %.3g ms, %ld segments %.3g ms (x%.2f for x%.1f size); brute force "
                "%ld segments %.3g ms\n",
                n1, 1e3 * t1, n2, 1e3 * t2, t2 / t1, double(n2) / n1, nb, 1e3 * tb);
}

// --- projection --------------------------------------------------------------------------------

TEST(ContactProjection, WarpedQuadClosestPointMatchesDenseSampling) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    const Vec3 a(0, 0, 0), b(1, 0, 0.2), c(1.1, 1, -0.1), d(0, 0.9, 0.15);  // non-planar
    for (int k = 0; k < 50; ++k) {
        const Vec3 p(0.5 + 0.8 * U(rng), 0.5 + 0.8 * U(rng), 0.3 * U(rng));
        const Projection pr = project_quad(p, a, b, c, d);
        // Dense sampling of the bilinear patch, then a local refinement.
        double best = 1e300, bx = 0, be = 0;
        auto X = [&](double xi, double eta) {
            return 0.25 * ((1 - xi) * (1 - eta) * a + (1 + xi) * (1 - eta) * b + (1 + xi) * (1 + eta) * c +
                           (1 - xi) * (1 + eta) * d);
        };
        for (int i = 0; i <= 400; ++i)
            for (int j = 0; j <= 400; ++j) {
                const double xi = -1 + i / 200.0, eta = -1 + j / 200.0, dd = (X(xi, eta) - p).norm();
                if (dd < best) best = dd, bx = xi, be = eta;
            }
        for (double h = 0.005; h > 1e-9; h *= 0.5)
            for (int i = -2; i <= 2; ++i)
                for (int j = -2; j <= 2; ++j) {
                    const double xi = std::clamp(bx + i * h, -1.0, 1.0), eta = std::clamp(be + j * h, -1.0, 1.0);
                    const double dd = (X(xi, eta) - p).norm();
                    if (dd < best) best = dd, bx = xi, be = eta;
                }
        EXPECT_NEAR(pr.distance, best, 1e-9) << "point " << p.transpose();
        EXPECT_NEAR((pr.point - X(pr.xi, pr.eta)).norm(), 0.0, 1e-12);
        double sumN = 0;
        for (double N : pr.shape) sumN += N;
        EXPECT_NEAR(sumN, 1.0, 1e-14);
    }
}

TEST(ContactProjection, TriangleRegionsAndSignedGap) {
    const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
    Projection p = project_triangle(Vec3(0.5, 0.5, -0.1), a, b, c);
    EXPECT_TRUE(p.inside);
    EXPECT_NEAR(p.gap, -0.1, 1e-15);
    EXPECT_NEAR(p.tangential_offset, 0.0, 1e-15);
    EXPECT_NEAR(p.shape[0], 0.5, 1e-15);
    EXPECT_NEAR(p.shape[1], 0.25, 1e-15);
    p = project_triangle(Vec3(2, 2, 0.3), a, b, c);  // beyond the hypotenuse
    EXPECT_FALSE(p.inside);
    EXPECT_NEAR((p.point - Vec3(1, 1, 0)).norm(), 0.0, 1e-15);
    EXPECT_NEAR(p.gap, 0.3, 1e-15);
    p = project_triangle(Vec3(-1, -1, 0), a, b, c);  // vertex region of a
    EXPECT_NEAR(p.point.norm(), 0.0, 1e-15);
    // Quad: flat square, interior point: exact (xi, eta) and gap.
    const Projection q = project_quad(Vec3(0.25, 0.75, 0.05), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0));
    EXPECT_TRUE(q.inside);
    EXPECT_NEAR(q.xi, -0.5, 1e-12);
    EXPECT_NEAR(q.eta, 0.5, 1e-12);
    EXPECT_NEAR(q.gap, 0.05, 1e-14);
}

// SegmentBox (projection.hpp): the box holds every point of the segment, so its distance bound never
// exceeds the projection's distance, and where the normal is bounded the height obeys
// -w + min(g, 0) - t <= h <= w + max(g, 0) + t. Random warped quads and triangles, rotated, with
// points all around (beside, in front, behind). The slack is round-off.
TEST(ContactProjection, SegmentBoxBoundsEveryProjection) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    int bounded = 0, checked = 0;
    for (int k = 0; k < 400; ++k) {
        const Eigen::Matrix3d R = Eigen::AngleAxisd(3.0 * U(rng), Vec3(U(rng), U(rng), U(rng)).normalized()).toRotationMatrix();
        const double warp = k % 4 == 0 ? 0.6 : 0.15;  // every fourth quad badly warped
        const Vec3 origin(U(rng), U(rng), U(rng));
        auto corner = [&](double x, double y) {
            return Vec3(origin + R * Vec3(x + 0.2 * U(rng), y + 0.2 * U(rng), warp * U(rng)));
        };
        const Vec3 a = corner(0, 0), b = corner(1, 0), c = corner(1, 1), d = corner(0, 1);
        const bool quad = k % 3 != 0;
        const SegmentBox box = quad ? segment_box(a, b, c, d) : segment_box(a, b, c);
        bounded += box.normal_bounded;
        for (int j = 0; j < 50; ++j) {
            const Vec3 p = origin + R * Vec3(0.5 + 1.5 * U(rng), 0.5 + 1.5 * U(rng), 0.8 * U(rng));
            const Projection pr = quad ? project_quad(p, a, b, c, d) : project_triangle(p, a, b, c);
            const double eps = 1e-12;
            EXPECT_LE(box.distance_below(p), pr.distance + eps) << "segment " << k << " point " << j;
            if (!box.normal_bounded) continue;
            ++checked;
            const double h = box.height(p);
            EXPECT_LE(h, box.w + std::max(pr.gap, 0.0) + pr.tangential_offset + eps) << "segment " << k << " point " << j;
            EXPECT_GE(h, -box.w + std::min(pr.gap, 0.0) - pr.tangential_offset - eps) << "segment " << k << " point " << j;
        }
    }
    EXPECT_GT(bounded, 300);  // the mildly warped ones at least
    EXPECT_GT(checked, 15000);
}

// --- penalty force -----------------------------------------------------------------------------

// A node pushed 1 mm into the top face of one hex: f_n = k |g| along the face normal (Eq 2-30,
// k = min of the two sides' Eq 2-30a values), the face nodes carry -N_i f, forces sum to zero.
TEST(ContactPenalty, ForceDirectionMagnitudeAndShapeFunctionSplit) {
    Mesh m = box_hex8(1.0, 1.0, 1.0, 1, 1, 1, "block");
    Mesh probe = box_hex8(0.2, 0.2, 0.2, 1, 1, 1, "probe");
    probe.translate(Vec3(0.2, 0.3, 0.999));  // its bottom face 1 mm below the block's top face
    m.append(probe);
    const ContactSurface block = ContactSurface::from_part(m, "block", kSteel);
    const ContactSurface small = ContactSurface::from_part(m, "probe", kTable31Rubber);
    ContactOptions o;
    o.penalty_scale = 0.5;
    ContactInterface ci("probe on block", small, block, o);
    std::vector<Vec3> f(m.node_count(), Vec3::Zero());
    ci.evaluate(m.nodes, {}, 0.0, 0.0, f);
    ASSERT_EQ(ci.contacts().size(), 4u);  // the probe's four bottom nodes
    const double B = kTable31Rubber.bulk_modulus();
    const double k = 0.5 * B * 0.04 * 0.04 / 0.008;  // SLSFAC x Eq 2-30a of the softer (rubber) side
    Vec3 sum = Vec3::Zero();
    for (const auto& cp : ci.contacts()) {
        EXPECT_NEAR(cp.gap, -1e-3, 1e-12);
        EXPECT_NEAR(cp.normal_force, k * 1e-3, 1e-9 * k);
        EXPECT_NEAR(f[cp.node].z(), k * 1e-3, 1e-9 * k);
        EXPECT_NEAR(cp.normal.z(), 1.0, 1e-14);
    }
    for (const auto& v : f) sum += v;
    EXPECT_NEAR(sum.norm(), 0.0, 1e-12 * k);
    // Block top node (1,1,1) is node 7 of box_hex8; it gets -sum N_7 f.
    double expect7 = 0;
    for (const auto& cp : ci.contacts()) {
        const Vec3& p = m.nodes[cp.node];
        expect7 += p.x() * p.y() * cp.normal_force;  // bilinear N of corner (1,1) on the unit square
    }
    EXPECT_NEAR(f[7].z(), -expect7, 1e-9 * k);
    EXPECT_NEAR(ci.stored_energy(), 4 * 0.5 * k * 1e-6, 1e-9 * k * 1e-6);
    EXPECT_NEAR(ci.force_on_master().z(), -4 * k * 1e-3, 1e-9 * k);
}

// Momentum: for random penetrating nodes with friction and random velocities the contact forces of
// every pair sum to zero, and their moment is that of the pair's offset g n x f_t only.
TEST(ContactPenalty, PairForcesConserveMomentumExactly) {
    Mesh m = box_hex8(1.0, 1.0, 0.3, 4, 4, 1, "base");
    Mesh top = box_hex8(0.6, 0.6, 0.2, 5, 5, 1, "top");
    top.translate(Vec3(0.2, 0.2, 0.3));
    m.append(top);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    std::vector<Vec3> x = m.nodes, v(m.node_count());
    for (int i = 0; i < m.node_count(); ++i) {
        x[i] += 0.004 * Vec3(U(rng), U(rng), U(rng));
        v[i] = Vec3(U(rng), U(rng), 0.1 * U(rng));
    }
    ContactOptions o;
    o.friction = {0.6, 0.4, 1.0};
    o.two_way = true;
    ContactInterface ci("top on base", ContactSurface::from_part(m, "top", kTable31Rubber),
                        ContactSurface::from_part(m, "base", kTable31Rubber), o);
    std::vector<Vec3> f(m.node_count(), Vec3::Zero());
    for (int cycle = 0; cycle < 3; ++cycle) {
        for (auto& fi : f) fi.setZero();
        ci.evaluate(x, v, cycle * 1e-4, 1e-4, f);
    }
    ASSERT_GT(ci.contacts().size(), 10u);
    Vec3 F = Vec3::Zero(), M = Vec3::Zero();
    double scale = 0, offset_moment = 0;
    for (int i = 0; i < m.node_count(); ++i) {
        F += f[i];
        M += x[i].cross(f[i]);
        scale += f[i].norm();
    }
    // Each pair's moment is (x_slave - x_point) x F: zero when the node projects exactly along the
    // normal and the force is normal; bounded by |x_slave - x_point| |F| otherwise.
    for (const auto& cp : ci.contacts())
        offset_moment += (cp.position - cp.point).norm() * (cp.normal_force * cp.normal + cp.tangential_force).norm();
    EXPECT_LT(F.norm(), 1e-13 * scale);
    EXPECT_LE(M.norm(), offset_moment * (1 + 1e-9) + 1e-13 * scale);
}

namespace {
// The probe tests below: part "probe" (rubber) against part "block" (rigid, depth limit 5 cm), the
// edge tolerance 0.05 of the face size (5 mm on the block's 0.1 m faces) stated, not defaulted.
ContactInterface probe_against_rigid_block(const Mesh& m, const std::string& name) {
    ContactOptions o;
    o.edge_tolerance = 0.05;
    return ContactInterface(name, ContactSurface::from_part(m, "probe", kTable31Rubber),
                            ContactSurface::rigid_part(m, "block", 0.05), o);
}
}  // namespace

// A node beside a thick block, level with its side, just outside its side face but within the
// edge tolerance of its bottom face (and behind that face's plane by less than the depth limit):
// it is outside the block and must get no force (the outside veto); moved 0.1 mm into the side
// face it is in contact with that face.
TEST(ContactPenalty, NodeBesideAThickBlockIsNotCapturedByAFarFace) {
    Mesh m = box_hex8(0.1, 0.1, 0.1, 1, 1, 1, "block");
    Mesh probe = box_hex8(0.01, 0.01, 0.01, 1, 1, 1, "probe");
    probe.translate(Vec3(0.1001, 0.05, 0.02));  // 0.1 mm outside the face x = 0.1, 20 mm above z = 0
    m.append(probe);
    // The edge tolerance (5 mm on the 0.1 m faces) puts the probe within the bottom face's.
    ContactInterface ci = probe_against_rigid_block(m, "probe beside block");
    std::vector<Vec3> f(m.node_count(), Vec3::Zero());
    ci.evaluate(m.nodes, {}, 0.0, 0.0, f);
    EXPECT_TRUE(ci.contacts().empty());
    std::vector<Vec3> x = m.nodes;
    for (int i = 8; i < 16; ++i) x[i].x() -= 0.0002;  // now 0.1 mm inside the side face
    ci.evaluate(x, {}, 0.0, 0.0, f);
    ASSERT_EQ(ci.contacts().size(), 4u);  // the probe's x-min face nodes
    for (const auto& cp : ci.contacts()) {
        EXPECT_NEAR(cp.normal.x(), 1.0, 1e-12);
        EXPECT_NEAR(cp.gap, -1e-4, 1e-12);
    }
}

// The same beside a convex vertical edge of the block (the faceted rim of rotating_finger_contact's
// object): the node is 0.5 mm in front of the side face x = 0.1 and 1 mm beyond its edge y = 0, so it
// projects onto neither side face from inside, only within their edge tolerance; 20 mm above the
// bottom face it lies within that face's edge tolerance and depth. It is outside the block: no force.
// (Before the veto counted faces the node is beside, within the edge tolerance, the bottom face took
// it with 20 mm of penetration: the 160 N spikes of rotating_finger_contact on finer finger meshes.)
TEST(ContactPenalty, NodeBesideAConvexEdgeIsNotCapturedByAFarFace) {
    Mesh m = box_hex8(0.1, 0.1, 0.1, 1, 1, 1, "block");
    Mesh probe = box_hex8(0.01, 0.01, 0.01, 1, 1, 1, "probe");
    probe.translate(Vec3(0.1005, -0.011, 0.02));  // x-min face 0.5 mm outside x = 0.1; y-max face 1 mm below y = 0
    m.append(probe);
    ContactInterface ci = probe_against_rigid_block(m, "probe beside edge");
    std::vector<Vec3> f(m.node_count(), Vec3::Zero());
    ci.evaluate(m.nodes, {}, 0.0, 0.0, f);
    EXPECT_TRUE(ci.contacts().empty());
    for (const Vec3& fi : f) EXPECT_EQ(fi.norm(), 0.0);
}

// The other side of the veto: a dent (a finger pressed into a soft object) makes a concave edge, and
// near it a node can be inside the body while in front of the neighbouring face's extended plane.
// Two rigid top faces meet in a valley 20 mm deep at x = 0.1; the probe's bottom nodes lie 3.5 and
// 1.5 mm short of the valley, 0.4-0.8 mm behind face A (projecting squarely into it) and 0.2-0.6 mm in
// front of face B's extended plane, beside B within its edge tolerance. They are inside: A keeps them.
// (When a face the node was only beside could veto any capture, these nodes went free.)
TEST(ContactPenalty, NodeInADentIsKeptByTheFaceItPenetrates) {
    Mesh m = box_hex8(0.2, 0.1, 0.1, 2, 1, 1, "block");
    for (Vec3& x : m.nodes)
        if (std::abs(x.x() - 0.1) < 1e-12 && std::abs(x.z() - 0.1) < 1e-12) x.z() -= 0.02;  // the valley
    Mesh probe = box_hex8(0.002, 0.002, 0.002, 1, 1, 1, "probe");
    probe.translate(Vec3(0.0965, 0.049, 0.0799));
    m.append(probe);
    ContactInterface ci = probe_against_rigid_block(m, "probe in a dent");
    std::vector<Vec3> f(m.node_count(), Vec3::Zero());
    ci.evaluate(m.nodes, {}, 0.0, 0.0, f);
    ASSERT_EQ(ci.contacts().size(), 4u);  // the probe's four bottom nodes
    for (const auto& c : ci.contacts()) {
        EXPECT_LT(c.gap, -3e-4);
        EXPECT_GT(c.normal.z(), 0.9);  // face A's outward normal (0.196, 0, 0.981)
        EXPECT_GT(c.normal.x(), 0.0);  // A, not B (-0.196, 0, 0.981)
    }
}

// --- friction ----------------------------------------------------------------------------------

// A node pressed on a fixed rigid plate (constant penetration, f_n fixed) and pulled along x at
// constant speed: the tangential force grows as k u (stick) until it reaches mu_s f_n at
// u = mu_s f_n / k, then the node slides with mu(v) f_n of Eq 2-35; dissipation = mu f_n x slip.
TEST(ContactFriction, StickUntilStaticLimitThenSlideWithEq235) {
    Mesh m = box_hex8(0.1, 0.1, 0.1, 1, 1, 1, "cube");
    m.append(parallelogram_quad4(Vec3(0.05, 0.05, 0.0), Vec3(2, 0, 0), Vec3(0, 2, 0), 1, 1, "plate"));
    const ContactSurface cube = ContactSurface::from_part(m, "cube", kTable31Rubber);
    ContactOptions o;
    o.friction = {0.8, 0.5, 20.0};  // mu_s, mu_d, c_d [s/m]
    ContactInterface ci("cube on plate", cube, ContactSurface::rigid_part(m, "plate", 0.05), o);
    const double g = 1e-4, dt = 1e-5, speed = 0.2;  // mu(0.2 m/s) = 0.5 + 0.3 e^-4
    const int n_cube = 8;  // the plate's 4 nodes follow: they stay where they are
    std::vector<Vec3> x = m.nodes, v(m.node_count(), Vec3::Zero());
    for (int i = 0; i < n_cube; ++i) x[i].z() -= g;
    std::vector<Vec3> f(m.node_count());
    const double mu_v = o.friction.mu(speed);
    EXPECT_NEAR(mu_v, 0.5 + 0.3 * std::exp(-4.0), 1e-15);
    EXPECT_NEAR(o.friction.mu(0.0), 0.8, 1e-15);
    EXPECT_NEAR(o.friction.mu(1.0 / 20.0), 0.5 + 0.3 / std::numbers::e, 1e-15);  // Eq 2-35 at v = 1/c_d
    int first_slip = -1;
    double kn = 0, fn = 0, slid = 0;
    for (int cycle = 0; cycle < 4000; ++cycle) {
        const bool moving = cycle > 0;
        for (int i = 0; i < n_cube; ++i) {
            v[i] = moving ? Vec3(speed, 0, 0) : Vec3::Zero();
            if (moving) x[i].x() += speed * dt;
        }
        for (auto& fi : f) fi.setZero();
        ci.evaluate(x, v, cycle * dt, moving ? dt : 0.0, f);
        ASSERT_EQ(ci.contacts().size(), 4u);
        const ContactPoint& cp = ci.contacts()[0];
        kn = cp.normal_force / g;
        fn = cp.normal_force;
        const double u = cycle * speed * dt;
        const double ft = -cp.tangential_force.x();
        if (!cp.slipping && first_slip < 0) {
            EXPECT_NEAR(ft, kn * u, 1e-9 * fn) << "stick: elastic spring, cycle " << cycle;
            EXPECT_LE(ft, 0.8 * fn * (1 + 1e-12));
        } else {
            if (first_slip < 0) first_slip = cycle;
            slid += speed * dt;
            EXPECT_NEAR(ft, mu_v * fn, 1e-9 * fn) << "slip: mu(v) f_n, cycle " << cycle;
        }
    }
    // The first slip happens where the spring force k u passes mu_s f_n... but the first moving
    // cycle already has v = 0.2 m/s, so the limit is mu(v) f_n: u_slip = mu(v) f_n / k.
    const double u_slip = mu_v * fn / kn;
    ASSERT_GT(first_slip, 0);
    EXPECT_NEAR(first_slip * speed * dt, u_slip, speed * dt);
    // Dissipation: 4 nodes x mu f_n x (total slide - the elastic stretch u_slip), f_n constant.
    const double plastic = 3999 * speed * dt - u_slip;
    EXPECT_NEAR(ci.dissipated_energy(), 4 * mu_v * fn * plastic, 1e-9 * 4 * mu_v * fn * plastic);
    EXPECT_NEAR(ci.stored_energy(), 4 * (0.5 * kn * g * g + std::pow(mu_v * fn, 2) / (2 * kn)), 1e-9 * ci.stored_energy());
}

// The same node pulled by a slowly growing force (c_d = 0: mu = mu_d whenever it slides; the static
// limit applies at zero relative speed): it sticks while the pull is below mu_s f_n.
TEST(ContactFriction, ReturnMapStickBelowStaticLimitAndSlideAtDynamic) {
    const FrictionLaw law{0.6, 0.4, 50.0};
    const Vec3 n = Vec3::UnitZ();
    const double k = 1e5, fn = 10.0;
    // Stick: a slip increment that loads the spring to 5 N (< mu_s fn = 6 N) with zero speed.
    FrictionUpdate r = coulomb_return_map(Vec3::Zero(), n, Vec3(-5e-5, 0, 0), 0.0, k, fn, law);
    EXPECT_FALSE(r.slipping);
    EXPECT_NEAR(r.force.x(), 5.0, 1e-12);
    // More slip at zero speed: capped at mu_s fn = 6 N.
    r = coulomb_return_map(r.force, n, Vec3(-2e-5, 0, 0), 0.0, k, fn, law);
    EXPECT_TRUE(r.slipping);
    EXPECT_NEAR(r.force.x(), 6.0, 1e-12);
    EXPECT_NEAR(r.dissipation, 6.0 * 1e-5, 1e-15);
    // Sliding fast: mu -> mu_d (exp(-50 x 1) ~ 2e-22).
    r = coulomb_return_map(r.force, n, Vec3(-1e-3, 0, 0), 1.0, k, fn, law);
    EXPECT_NEAR(r.force.x(), 4.0, 1e-12);
    // Reversal: unloads elastically (stick) until the opposite limit.
    r = coulomb_return_map(r.force, n, Vec3(5e-5, 0, 0), 0.0, k, fn, law);
    EXPECT_FALSE(r.slipping);
    EXPECT_NEAR(r.force.x(), -1.0, 1e-12);
    // The stored force follows a rotating tangent plane with its magnitude kept.
    const Vec3 n2 = Vec3(0.0, std::sin(0.1), std::cos(0.1));
    r = coulomb_return_map(Vec3(0, 3, 0), n2, Vec3::Zero(), 0.0, k, fn, law);
    EXPECT_NEAR(r.force.norm(), 3.0, 1e-12);
    EXPECT_NEAR(r.force.dot(n2), 0.0, 1e-12);
    EXPECT_THROW((FrictionLaw{-0.1, 0.1, 0}.validate("test")), InputError);
}

// --- two-way contact ----------------------------------------------------------------------------

// A coarse block (one element, 1 m wide) on a fine, narrower pad whose top nodes poke into the
// block's bottom face: the block's own nodes (its corners) are outside the pad, so one-way contact
// (block nodes vs pad faces) sees nothing; two-way also checks the pad's nodes against the block's
// faces and pushes the block up.
TEST(ContactTwoWay, SymmetricPassCatchesMasterNodesInsideSlaveFaces) {
    Mesh m = box_hex8(1.0, 1.0, 1.0, 1, 1, 1, "block");
    Mesh pad = box_hex8(0.5, 0.5, 0.2, 4, 4, 1, "pad");
    pad.translate(Vec3(0.25, 0.25, -0.199));  // pad top 1 mm above the block's bottom face z = 0
    m.append(pad);
    for (bool two_way : {false, true}) {
        ContactOptions o;
        o.two_way = two_way;
        ContactInterface ci("block on pad", ContactSurface::from_part(m, "block", kTable31Rubber),
                            ContactSurface::from_part(m, "pad", kTable31Rubber), o);
        std::vector<Vec3> f(m.node_count(), Vec3::Zero());
        ci.evaluate(m.nodes, {}, 0.0, 0.0, f);
        double fz_block = 0;
        for (int i = 0; i < 8; ++i) fz_block += f[i].z();
        if (!two_way) {
            EXPECT_TRUE(ci.contacts().empty());
            EXPECT_EQ(fz_block, 0.0);
        } else {
            EXPECT_EQ(ci.contacts().size(), 25u);  // the pad's 5 x 5 top nodes
            EXPECT_GT(fz_block, 0.0);              // the pad pushes the block up
        }
    }
}

// --- rigid bodies ------------------------------------------------------------------------------

// A rigid part's surface (the model moves its nodes: here the test puts them where the motion
// says) pushes nodes, and the reaction on it (force and moment) is minus what its contacts put on
// the slave nodes; the rigid master's nodes receive no forces.
TEST(RigidMasterTest, RotatingRigidPartPushesNodesAndReportsTheReaction) {
    Mesh m = box_hex8(0.2, 0.2, 0.2, 2, 2, 2, "drum");
    m.translate(Vec3(-0.1, -0.1, -0.1));
    Mesh probe = box_hex8(0.05, 0.05, 0.05, 1, 1, 1, "probe");
    probe.translate(Vec3(0.099, -0.025, -0.025));  // its x-min face 1 mm inside the cube's x = 0.1 face
    m.append(probe);
    const RigidMotion motion = RigidMotion::rotation(Vec3::Zero(), Vec3::UnitZ(), Curve::constant(1.0));
    ContactSurface drum = ContactSurface::rigid_part(m, "drum", 0.02);
    EXPECT_TRUE(drum.rigid);
    EXPECT_TRUE(drum.nodes.empty());
    EXPECT_EQ(drum.segments.size(), 24u);
    ContactInterface ci("probe on drum", ContactSurface::from_part(m, "probe", kTable31Rubber), std::move(drum));
    EXPECT_TRUE(ci.rigid_master());
    std::vector<Vec3> f(m.node_count(), Vec3::Zero());
    ci.evaluate(m.nodes, {}, 0.0, 0.0, f);
    ASSERT_EQ(ci.contacts().size(), 4u);
    Vec3 F = Vec3::Zero(), M = Vec3::Zero();
    for (int i = 0; i < m.node_count(); ++i) {
        F += f[i];
        M += m.nodes[i].cross(f[i]);
    }
    for (int i = 0; i < 27; ++i) EXPECT_EQ(f[i], Vec3::Zero()) << i;  // the drum's nodes
    EXPECT_GT(F.x(), 0.0);
    EXPECT_NEAR((ci.force_on_master() + F).norm(), 0.0, 1e-12 * F.norm());
    // The moment about the axis: frictionless forces on the x face are along x, so the moments
    // of the nodes (y = -0.025 and 0.025) cancel; compare both sides anyway.
    const Resultant r = resultant(std::vector<int>{27, 28, 29, 30, 31, 32, 33, 34}, f, m.nodes, Vec3::Zero());
    EXPECT_NEAR((ci.moment_on_master(Vec3::Zero()) + r.moment).norm(), 0.0, 1e-9 * F.norm());
    EXPECT_NEAR(ci.max_penetration(), 1e-3, 1e-12);
    EXPECT_NEAR(ci.max_penetration_fraction(), 1e-3 / 0.05, 1e-10);  // of the probe's 50 mm element
    // After a half turn (t = pi at 1 rad/s) the cube covers itself: the face that was at x = -0.1
    // is now at x = 0.1 and the same four nodes are 1 mm deep again, against a different segment.
    const int seg0 = ci.contacts()[0].segment;
    std::vector<Vec3> x = m.nodes;
    for (int i = 0; i < 27; ++i) x[i] = motion.position(m.nodes[i], std::numbers::pi);
    EXPECT_NEAR((x[0] - Vec3(-m.nodes[0].x(), -m.nodes[0].y(), m.nodes[0].z())).norm(), 0.0, 1e-15);
    for (auto& fi : f) fi.setZero();
    ci.evaluate(x, {}, std::numbers::pi, 0.0, f);
    ASSERT_EQ(ci.contacts().size(), 4u);
    EXPECT_NE(ci.contacts()[0].segment, seg0);
    EXPECT_NEAR(ci.contacts()[0].gap, -1e-3, 1e-12);
    EXPECT_THROW(ContactSurface::rigid_part(m, "drum", 0.0), InputError);
    // A rigid side is a master only; two-way contact needs a deformable master.
    EXPECT_THROW(ContactInterface("bad", ContactSurface::rigid_part(m, "drum", 0.02),
                                  ContactSurface::from_part(m, "probe", kTable31Rubber)),
                 InputError);
    ContactOptions two;
    two.two_way = true;
    EXPECT_THROW(ContactInterface("bad", ContactSurface::from_part(m, "probe", kTable31Rubber),
                                  ContactSurface::rigid_part(m, "drum", 0.02), two),
                 InputError);
    ContactOptions bad;
    bad.penalty_scale = 0.0;
    EXPECT_THROW(ContactInterface("bad", ContactSurface::from_part(m, "probe", kTable31Rubber),
                                  ContactSurface::rigid_part(m, "drum", 0.02), bad),
                 InputError);
}

// The ball mesh of the Hertz tests: valid elements, surface close to the sphere's.
#include "ball_mesh.hpp"
TEST(ContactSurface, BallMeshIsValidAndItsSurfaceIsASphere) {
    const double R = 0.05;
    const Mesh m = fem::test::ball_hex8(R, 12, 0.5, 0.5);
    EXPECT_NO_THROW(validate(m));
    const ContactSurface s = ContactSurface::from_part(m, "ball", kTable31Rubber);
    EXPECT_EQ(s.segments.size(), 6u * 12 * 12);
    double area = 0;
    for (const auto& seg : s.segments) area += seg.area;
    // Bilinear facets are chords of the sphere: the area falls short by O(h^2), ~1 % at n = 12.
    EXPECT_NEAR(area / (4 * std::numbers::pi * R * R), 1.0, 0.02);
    for (int node : s.nodes) EXPECT_NEAR(m.nodes[node].norm(), R, 1e-12);
}

// ContactOptions::skip_far_candidates projects a node only onto the candidates that may capture it or
// veto its capture; it must give what projecting every candidate gives, to the last bit: forces,
// contact points, energies, cycle after cycle with friction history. A ball pressed into a block with
// a warped top (two-way, friction), sliding and turning over it, then lifted off; and a shell probe
// pushed through a shell plate with thickness (two-sided segments, offsets).
TEST(ContactPenalty, SkippingFarCandidatesChangesNothing) {
    struct Scenario {
        std::string name;
        Mesh mesh;
        ContactSurface slave, master;
        ContactOptions options;
        std::function<Vec3(const Vec3&, double)> move;  // slave node at reference X, time fraction s
    };
    std::vector<Scenario> scenarios;
    {
        Mesh m = box_hex8(0.2, 0.2, 0.05, 8, 8, 2, "block");
        std::mt19937 rng(3);
        std::uniform_real_distribution<double> U(-1.0, 1.0);
        for (Vec3& x : m.nodes)
            if (x.z() > 0.049) x.z() += 0.002 * U(rng);  // warped top faces
        Mesh ball = fem::test::ball_hex8(0.03, 6, 0.6, 0.6);
        ball.translate(Vec3(0.07, 0.08, 0.05 + 0.03 + 0.003));  // 3 mm above the top
        m.append(ball);
        ContactOptions o;
        o.friction = {0.4, 0.3, 10.0};
        o.two_way = true;
        Scenario sc{"ball on block", m, ContactSurface::from_part(m, "ball", kTable31Rubber),
                    ContactSurface::from_part(m, "block", kTable31Rubber), o, {}};
        const Vec3 c0(0.07, 0.08, 0.083);
        sc.move = [c0](const Vec3& X, double s) {
            // Down 10 mm (its flattened bottom 4.5 mm into the block) in the first third, slide 60 mm in
            // x turning 0.5 rad about y, up again in the last fifth.
            const double down = 0.010 * std::min(1.0, 3.0 * s) - (s > 0.8 ? 0.04 * (s - 0.8) : 0.0);
            const Eigen::Matrix3d R = Eigen::AngleAxisd(0.5 * s, Vec3::UnitY()).toRotationMatrix();
            Vec3 r = R * (X - c0);
            if (r.z() < -0.025) r.z() = -0.025 + 0.5 * (r.z() + 0.025);
            return Vec3(c0 + r + Vec3(0.06 * s, 0.01 * s, -down));
        };
        scenarios.push_back(std::move(sc));
    }
    {
        Mesh m = rectangle_quads(0.1, 0.1, 6, 6, ElementShape::Quad4, "plate");
        Mesh probe = rectangle_quads(0.03, 0.03, 3, 3, ElementShape::Quad4, "probe");
        probe.translate(Vec3(0.02, 0.03, 0.004));
        m.append(probe);
        ContactOptions o;
        o.friction = {0.3, 0.3, 0.0};
        Scenario sc{"shell probe on shell plate", m, ContactSurface::from_part(m, "probe", kSteel, 1.0, 0.002),
                    ContactSurface::from_part(m, "plate", kSteel, 1.0, 0.002), o, {}};
        sc.move = [](const Vec3& X, double s) {  // down through the offsets, tilting, sliding in x
            return Vec3(X + Vec3(0.04 * s, 0.0, -0.0035 * std::sin(3.0 * s) - 0.002 * (X.x() - 0.035) * s));
        };
        scenarios.push_back(std::move(sc));
    }
    for (auto& sc : scenarios) {
        ContactOptions reference = sc.options;
        reference.skip_far_candidates = false;
        ContactInterface all(sc.name, sc.slave, sc.master, reference), skip(sc.name, sc.slave, sc.master, sc.options);
        std::set<int> slave_nodes;
        for (const auto& seg : sc.slave.segments)
            for (int k = 0; k < seg.count; ++k) slave_nodes.insert(seg.n[k]);
        const int cycles = 400;
        const double dt = 1e-5;
        std::vector<Vec3> x = sc.mesh.nodes, x_old = x, v(x.size(), Vec3::Zero());
        long contacts = 0;
        for (int cycle = 0; cycle < cycles; ++cycle) {
            for (int n : slave_nodes) x[n] = sc.move(sc.mesh.nodes[n], static_cast<double>(cycle) / cycles);
            for (std::size_t n = 0; n < x.size(); ++n) v[n] = (x[n] - x_old[n]) / dt;
            x_old = x;
            std::vector<Vec3> fa(x.size(), Vec3::Zero()), fs(x.size(), Vec3::Zero());
            all.evaluate(x, v, cycle * dt, dt, fa);
            skip.evaluate(x, v, cycle * dt, dt, fs);
            for (std::size_t n = 0; n < x.size(); ++n)
                ASSERT_TRUE(fa[n] == fs[n]) << sc.name << " cycle " << cycle << " node " << n << ": " << fa[n].transpose()
                                            << " vs " << fs[n].transpose();
            ASSERT_EQ(all.contacts().size(), skip.contacts().size()) << sc.name << " cycle " << cycle;
            for (std::size_t k = 0; k < all.contacts().size(); ++k) {
                EXPECT_EQ(all.contacts()[k].segment, skip.contacts()[k].segment);
                EXPECT_EQ(all.contacts()[k].gap, skip.contacts()[k].gap);
            }
            ASSERT_EQ(all.stored_energy(), skip.stored_energy()) << sc.name << " cycle " << cycle;
            ASSERT_EQ(all.dissipated_energy(), skip.dissipated_energy()) << sc.name << " cycle " << cycle;
            contacts += static_cast<long>(all.contacts().size());
        }
        EXPECT_EQ(all.max_penetration(), skip.max_penetration());
        fmt::print("{}: {} contacts over {} cycles; projections {} (every candidate) -> {} ({:.0f} %)\n", sc.name,
                   contacts, cycles, all.projections(), skip.projections(),
                   100.0 * static_cast<double>(skip.projections()) / static_cast<double>(all.projections()));
        EXPECT_GT(contacts, 2L * cycles) << sc.name << ": the scenario must keep many nodes in contact";
        EXPECT_GT(all.dissipated_energy(), 0.0) << sc.name << ": and slide with friction";
        EXPECT_LT(skip.projections(), all.projections()) << sc.name;
    }
}

namespace {
// A thin rigid plate 0.1 x 0.1 m at y = 0, its contact side +y (u x v), depth limit 5 mm (its
// "thickness"), and a 10 mm rubber probe cube; the probe's bottom nodes are the ones that matter.
struct PlateAndProbe {
    Mesh m;
    std::vector<int> bottom;  // the probe's nodes at its lowest y
    PlateAndProbe(const Vec3& probe_corner) {
        m = parallelogram_quad4(Vec3::Zero(), Vec3(0.1, 0, 0), Vec3(0, 0, -0.1), 2, 2, "plate");
        Mesh probe = box_hex8(0.01, 0.01, 0.01, 1, 1, 1, "probe");
        probe.translate(probe_corner);
        const int first = m.node_count();
        m.append(probe);
        for (int i = first; i < m.node_count(); ++i)
            if (m.nodes[i].y() == probe_corner.y()) bottom.push_back(i);
    }
    ContactInterface contact(bool track) const {
        ContactOptions o;
        o.edge_tolerance = 0.05;
        o.track_approach_side = track;
        return ContactInterface(track ? "tracked" : "depth rule", ContactSurface::from_part(m, "probe", kTable31Rubber),
                                ContactSurface::rigid_part(m, "plate", 5e-3), o);
    }
    // The probe moved by d, evaluated: the number of contacts.
    std::size_t contacts_at(ContactInterface& ci, const Vec3& d) const {
        std::vector<Vec3> x = m.nodes, f(m.node_count(), Vec3::Zero());
        for (int i = m.node_count() - 8; i < m.node_count(); ++i) x[i] += d;
        ci.evaluate(x, {}, 0.0, 0.0, f);
        return ci.contacts().size();
    }
};
}  // namespace

// ContactOptions::track_approach_side. A probe 3 mm below a thin plate's plane, beyond its edge
// (x = 0.05 m), slides under the plate (a leg crossing the plane of the shackle plate near its
// gripper end). The depth rule captures its bottom nodes as soon as they are inside the outline (3 mm
// behind the face, within the 5 mm depth: the spring would shoot them up through the plate); tracked,
// they came from behind and are never captured.
TEST(ContactTrackedSide, NodeComingRoundTheEdgeFromBehindIsNotCaptured) {
    const PlateAndProbe s(Vec3(0.056, -0.003, -0.005));
    ContactInterface depth_rule = s.contact(false), tracked = s.contact(true);
    std::size_t captured_by_depth_rule = 0;
    for (int k = 0; k <= 30; ++k) {  // 1 mm per evaluation towards -x: 30 mm under the plate at the end
        const Vec3 d(-1e-3 * k, 0, 0);
        captured_by_depth_rule = std::max(captured_by_depth_rule, s.contacts_at(depth_rule, d));
        EXPECT_EQ(s.contacts_at(tracked, d), 0u) << "at " << k << " mm";
    }
    EXPECT_EQ(captured_by_depth_rule, 4u);  // the four bottom nodes, once inside the outline
}

// A probe pressed into the plate from in front is held as by the depth rule, the same forces at
// every depth down to the limit; pushed beyond the limit it is let go (both rules), and coming back
// within it, tracked, it is still the node that came from in front: captured again. A probe that starts 1 mm into the
// plate (not yet seen near a face) follows the depth rule: captured.
TEST(ContactTrackedSide, NodePressedFromInFrontIsHeldAsByTheDepthRule) {
    const PlateAndProbe s(Vec3(-0.005, 0.002, -0.005));
    ContactInterface depth_rule = s.contact(false), tracked = s.contact(true);
    for (double y : {0.0, -1e-3, -2e-3, -3e-3, -4e-3, -4.9e-3, -6e-3, -4e-3}) {  // the probe's bottom, from 2 mm above
        const Vec3 d(0, y - 0.002, 0);
        const std::size_t n = s.contacts_at(depth_rule, d);
        EXPECT_EQ(s.contacts_at(tracked, d), n) << "bottom at " << y;
        EXPECT_EQ(n, y < 0.0 && y > -5e-3 ? 4u : 0u) << "bottom at " << y;
        if (n == 4u)
            for (std::size_t c = 0; c < 4; ++c) {
                EXPECT_EQ(tracked.contacts()[c].gap, depth_rule.contacts()[c].gap);
                EXPECT_EQ(tracked.contacts()[c].normal_force, depth_rule.contacts()[c].normal_force);
            }
    }
    const PlateAndProbe start_inside(Vec3(-0.005, -0.001, -0.005));
    ContactInterface first_seen_inside = start_inside.contact(true);
    EXPECT_EQ(start_inside.contacts_at(first_seen_inside, Vec3::Zero()), 4u);
}

// The side each node was last seen on is part of the interface's restart state: the probe of the
// first test, halfway under the plate, saved and restored into a fresh interface, is still not
// captured; a fresh interface that never saw it come from behind captures it (the depth rule for a
// node not yet seen); a tracked interface refuses a file written without the sides. A master with
// two-sided shell faces is refused.
TEST(ContactTrackedSide, ApproachSidesAreRestartStateAndTwoSidedMastersAreRefused) {
    const PlateAndProbe s(Vec3(0.056, -0.003, -0.005));
    ContactInterface tracked = s.contact(true);
    for (int k = 0; k <= 15; ++k) EXPECT_EQ(s.contacts_at(tracked, Vec3(-1e-3 * k, 0, 0)), 0u);
    const std::filesystem::path file = std::filesystem::temp_directory_path() / "fem_contact_tracked_side.h5";
    {
        io::H5Writer w(file);
        tracked.save_state(w, "contact/");
        w.commit();
    }
    ContactInterface restored = s.contact(true), fresh = s.contact(true), untracked = s.contact(false);
    restored.restore_state(io::H5Reader(file), "contact/");
    const Vec3 under(-16e-3, 0, 0);
    EXPECT_EQ(s.contacts_at(restored, under), 0u);
    EXPECT_EQ(s.contacts_at(fresh, under), 4u);
    {
        io::H5Writer w(file);
        untracked.save_state(w, "contact/");
        w.commit();
    }
    EXPECT_THROW(fresh.restore_state(io::H5Reader(file), "contact/"), InputError);  // a file without the sides
    std::filesystem::remove(file);

    Mesh m = parallelogram_quad4(Vec3::Zero(), Vec3(0.1, 0, 0), Vec3(0, 0, -0.1), 2, 2, "sheet");
    Mesh probe = box_hex8(0.01, 0.01, 0.01, 1, 1, 1, "probe");
    probe.translate(Vec3(0, 0.01, 0));
    m.append(probe);
    ContactOptions o;
    o.track_approach_side = true;
    EXPECT_THROW(ContactInterface("sheet", ContactSurface::from_part(m, "probe", kTable31Rubber),
                                  ContactSurface::from_part(m, "sheet", kSteel, 1.0, 0.002), o),
                 InputError);
}
