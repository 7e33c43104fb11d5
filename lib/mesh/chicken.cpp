#include "mesh/chicken.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/units.hpp"
#include "mesh/gmsh.hpp"
#include "mesh/mesh_tools.hpp"

namespace fem::chicken {
namespace {

using units::deg;
using units::mm;
namespace occ = gmsh::model::occ;

constexpr double kBig = 1.0;  // [m] far beyond any bird: extent of half-space boxes and bores

// --- Table 5-1 --------------------------------------------------------------------------------------
// Joint locations relative to the ellipsoid's geometric centre [mm].
const std::array<Vec3, 4> kTable51Joints = {Vec3(-24.72, -67.3, 40.0), Vec3(49.0, -51.6, 40.0),
                                            Vec3(-15.74, -10.74, 40.0), Vec3(43.37, 27.89, 35.0)};

Vec3 xy(const Vec3& p) { return Vec3(p.x(), p.y(), 0.0); }

// The leg's entities of one side (side = +1: z > 0 as in Table 5-1, -1: the mirror image).
Vec3 mirrored(const Vec3& p, int side) { return Vec3(p.x(), p.y(), side * p.z()); }

// A box of length `length` along the side-view direction `angle` from `start`, `width` across it in
// the x-y plane, spanning z0..z1.
int oriented_box(const Vec3& start, double angle, double length, double width, double z0, double z1,
                 double back = 0.0) {
    const int box = occ::addBox(-back, -0.5 * width, z0, length + back, width, z1 - z0);
    occ::rotate({{3, box}}, 0, 0, 0, 0, 0, 1, angle);
    occ::translate({{3, box}}, start.x(), start.y(), 0.0);
    return box;
}

// Bars of limb i (one box per depth half) of one side.
gmsh::vectorpair limb_bars(const Leg& leg, int i, int side) {
    const Limb& l = leg.limbs[i];
    const Vec3 a = leg.joints[i];
    const double angle = leg.limb_angle(i), length = leg.limb_length(i), zc = side * leg.plane_z();
    gmsh::vectorpair out;
    if (l.depth_lower == l.depth_upper) {
        out.push_back({3, oriented_box(a, angle, length, l.width, zc - 0.5 * l.depth_lower, zc + 0.5 * l.depth_lower)});
    } else {
        const Vec3 mid = a + 0.5 * length * Vec3(std::cos(angle), std::sin(angle), 0.0);
        out.push_back({3, oriented_box(a, angle, 0.5 * length, l.width, zc - 0.5 * l.depth_lower, zc + 0.5 * l.depth_lower)});
        out.push_back({3, oriented_box(mid, angle, 0.5 * length, l.width, zc - 0.5 * l.depth_upper, zc + 0.5 * l.depth_upper)});
    }
    return out;
}

// Knuckle of the hinge at joint j (1 .. n-2) and its hole (a bore through everything).
int knuckle(const Leg& leg, int j, int side) {
    const HoleHinge& h = leg.hinges[j - 1];
    const Vec3 p = leg.joints[j];
    const double zc = side * leg.plane_z();
    return occ::addCylinder(p.x(), p.y(), zc - 0.5 * h.depth, 0, 0, h.depth, h.hole_radius + h.neck);
}
int hole(const Leg& leg, int j, int side) {
    const Vec3 p = leg.joints[j];
    const double zc = side * leg.plane_z();
    return occ::addCylinder(p.x(), p.y(), zc - kBig, 0, 0, 2.0 * kBig, leg.hinges[j - 1].hole_radius);
}

// Fuses a list of volumes into `out` (one call; an empty or single list is returned as is).
gmsh::vectorpair fuse_all(gmsh::vectorpair v) {
    if (v.size() < 2) return v;
    gmsh::vectorpair object = {v.front()}, tools(v.begin() + 1, v.end()), out;
    std::vector<gmsh::vectorpair> map;
    occ::fuse(object, tools, out, map);
    return out;
}
gmsh::vectorpair cut(const gmsh::vectorpair& object, const gmsh::vectorpair& tools) {
    if (tools.empty()) return object;
    gmsh::vectorpair out;
    std::vector<gmsh::vectorpair> map;
    occ::cut(object, tools, out, map);
    return out;
}

// One whole leg: bars and knuckles fused, holes bored, hip bricks added.
gmsh::vectorpair leg_solid(const Leg& leg, int side) {
    gmsh::vectorpair parts, holes;
    for (int i = 0; i < leg.limb_count(); ++i)
        for (const auto& b : limb_bars(leg, i, side)) parts.push_back(b);
    for (int j = 1; j + 1 < static_cast<int>(leg.joints.size()); ++j) {
        parts.push_back({3, knuckle(leg, j, side)});
        holes.push_back({3, hole(leg, j, side)});
    }
    gmsh::vectorpair solid = cut(fuse_all(parts), holes);
    const Vec3 hip = mirrored(leg.joints.back(), side);
    const double last = leg.limb_angle(leg.limb_count() - 1);
    for (const HipBrick& b : leg.hip) {
        const int box = occ::addBox(-0.5 * b.length, -0.5 * b.height, -0.5 * b.thickness, b.length, b.height, b.thickness);
        occ::rotate({{3, box}}, 0, 0, 0, 0, 0, 1, last + (b.along_limb ? 0.0 : 0.5 * std::numbers::pi));
        occ::translate({{3, box}}, hip.x(), hip.y(), hip.z());
        solid.push_back({3, box});
    }
    return fuse_all(solid);
}

// The groove cut from the body around one leg: the leg's outline grown by the gap, from the leg's
// inner face (less the gap) out through the body's side.
gmsh::vectorpair leg_pocket(const Leg& leg, int side) {
    const double g = leg.pocket_gap, zc = leg.plane_z();
    auto z_range = [&](double depth) {
        const double inner = zc - 0.5 * depth - g, outer = zc + kBig;
        return side > 0 ? std::make_pair(inner, outer) : std::make_pair(-outer, -inner);
    };
    gmsh::vectorpair tools;
    for (int i = 0; i < leg.limb_count(); ++i) {
        const Limb& l = leg.limbs[i];
        const auto [z0, z1] = z_range(std::max(l.depth_lower, l.depth_upper));
        tools.push_back({3, oriented_box(leg.joints[i], leg.limb_angle(i), leg.limb_length(i) + g, l.width + 2.0 * g, z0, z1, g)});
    }
    for (int j = 1; j + 1 < static_cast<int>(leg.joints.size()); ++j) {
        const HoleHinge& h = leg.hinges[j - 1];
        const double depth = std::max({h.depth, leg.limbs[j - 1].depth_upper, leg.limbs[j].depth_lower});
        const auto [z0, z1] = z_range(depth);
        const Vec3 p = leg.joints[j];
        tools.push_back({3, occ::addCylinder(p.x(), p.y(), z0, 0, 0, z1 - z0, h.hole_radius + h.neck + g)});
    }
    return tools;
}

// The whole bird in the current Gmsh model; returns its volumes (one expected).
gmsh::vectorpair bird_solid(const Chicken& c, bool half) {
    const int sphere = occ::addSphere(0, 0, 0, 1.0);
    occ::dilate({{3, sphere}}, 0, 0, 0, c.body_a, c.body_b, c.body_c);
    gmsh::vectorpair pockets = leg_pocket(c.leg, +1);
    for (const auto& t : leg_pocket(c.leg, -1)) pockets.push_back(t);
    gmsh::vectorpair parts = cut({{3, sphere}}, pockets);

    const Vec3 h = c.head_center();
    const int head = occ::addSphere(0, 0, 0, 1.0);
    occ::dilate({{3, head}}, 0, 0, 0, c.head_a, c.head_b, c.head_c);
    occ::translate({{3, head}}, h.x(), h.y(), h.z());
    parts.push_back({3, head});
    parts.push_back({3, occ::addCylinder(h.x(), 0, 0, c.neck_root_x - h.x(), 0, 0, c.neck_radius)});
    for (int side : {+1, -1})
        for (const auto& v : leg_solid(c.leg, side)) parts.push_back(v);
    gmsh::vectorpair bird = fuse_all(parts);
    if (half) {
        const int box = occ::addBox(-kBig, -kBig, 0.0, 2.0 * kBig, 2.0 * kBig, kBig);
        gmsh::vectorpair out;
        std::vector<gmsh::vectorpair> map;
        occ::intersect(bird, {{3, box}}, out, map);
        bird = out;
    }
    return bird;
}

// Limb i (0-based) alone with the knuckles of its hinge joints.
gmsh::vectorpair limb_solid(const Leg& leg, int i) {
    gmsh::vectorpair parts = limb_bars(leg, i, +1), holes;
    for (int j : {i, i + 1})
        if (j >= 1 && j + 1 < static_cast<int>(leg.joints.size())) {
            parts.push_back({3, knuckle(leg, j, +1)});
            holes.push_back({3, hole(leg, j, +1)});
        }
    return cut(fuse_all(parts), holes);
}

// Volume, centroid and inertia about the centroid (unit density) of a set of volumes.
MassProperties properties(const gmsh::vectorpair& volumes) {
    MassProperties p;
    Mat3 about_origin = Mat3::Zero();
    for (const auto& [d, t] : volumes) {
        double m = 0.0, x = 0.0, y = 0.0, z = 0.0;
        std::vector<double> inertia;
        occ::getMass(d, t, m);
        occ::getCenterOfMass(d, t, x, y, z);
        occ::getMatrixOfInertia(d, t, inertia);  // about the entity's own centre of mass
        const Vec3 c(x, y, z);
        const Mat3 I = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(inertia.data());
        // Parallel axes to the origin: I_O = I_G + m (|c|^2 1 - c c^T).
        about_origin += I + m * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
        p.volume += m;
        p.centroid += m * c;
    }
    p.centroid /= p.volume;
    const Vec3& c = p.centroid;
    p.inertia = about_origin - p.volume * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
    return p;
}

std::vector<int> volume_tags(const gmsh::vectorpair& v) {
    std::vector<int> tags;
    for (const auto& [d, t] : v)
        if (d == 3) tags.push_back(t);
    return tags;
}

void set_mesh_options(double size_min, double size_max, int order, const std::string& who) {
    if (!(size_min > 0.0) || !(size_max >= size_min) || !std::isfinite(size_max))
        throw InputError(fmt::format("{}: mesh sizes must satisfy 0 < min <= max (got {} and {} m)", who, size_min, size_max));
    if (order != 1 && order != 2) throw InputError(fmt::format("{}: order must be 1 (tet4) or 2 (tet10), got {}", who, order));
    gmsh::option::setNumber("Mesh.MeshSizeMin", size_min);
    gmsh::option::setNumber("Mesh.MeshSizeMax", size_max);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
    gmsh::option::setNumber("Mesh.Algorithm", 6);    // Frontal-Delaunay surfaces
    gmsh::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay
    gmsh::option::setNumber("Mesh.Optimize", 1);     // removes most slivers (they would set the step)
    gmsh::option::setNumber("Mesh.SecondOrderLinear", 0);  // tet10 mid-edge nodes on the true surface
}

void generate(int order, const std::string& who) {
    try {
        gmsh::model::mesh::generate(3);
        if (order == 2) gmsh::model::mesh::setOrder(2);
    } catch (const std::string& e) {
        throw SolverError(who + ": Gmsh failed to mesh: " + e);
    }
}

// Every node of the mesh on the plane through p with unit normal n, within `radius` of p.
std::vector<int> nodes_on_plane(const Mesh& m, const Vec3& p, const Vec3& n, double radius, double tol) {
    return m.select_nodes([&](const Vec3& x) { return std::abs((x - p).dot(n)) < tol && (x - p).norm() < radius; });
}
// Every node on the wall of a hole of radius r bored along z through (p.x, p.y), within |z - p.z| < half_depth.
std::vector<int> nodes_on_bore(const Mesh& m, const Vec3& p, double r, double half_depth, double tol) {
    return m.select_nodes([&](const Vec3& x) {
        return std::abs((xy(x) - xy(p)).norm() - r) < tol && std::abs(x.z() - p.z()) < half_depth + tol;
    });
}

int node_at(const Mesh& m, const Vec3& p, double tol, const std::string& what) {
    const int best = nearest_node(m, p);
    const double d = (m.nodes[best] - p).norm();
    if (d > tol)
        throw SolverError(fmt::format("chicken_mesh: no node at the {} ({:.3g} mm away)", what, d / mm));
    return best;
}

template <class F>
auto with_model(const std::string& name, F&& body) {
    GmshSession session;
    gmsh::clear();
    try {
        gmsh::model::add(name);
        auto result = body();
        gmsh::clear();
        return result;
    } catch (const std::string& e) {  // the Gmsh API throws its error message
        gmsh::clear();
        throw SolverError(name + ": Gmsh failed to build the geometry: " + e);
    } catch (...) {
        gmsh::clear();
        throw;
    }
}

Limb bar(double width, double depth) { return {width, depth, depth}; }

}  // namespace

double Leg::limb_length(int i) const { return (xy(joints[i + 1]) - xy(joints[i])).norm(); }
double Leg::limb_angle(int i) const {
    const Vec3 d = joints[i + 1] - joints[i];
    return std::atan2(d.y(), d.x());
}

std::array<double, 3> calibrated_widths_table_5_1() {
    // Calibrated by `chicken_shackling --calibrate` (study README, "Calibration of the limbs").
    return {4.38 * mm, 12.99 * mm, 21.23 * mm};
}

Chicken table_5_1_chicken() {
    Chicken c;
    c.name = "Table 5-1 (body-grasping, L = 250 mm)";
    c.body_a = 97.0 * mm;
    c.body_b = 57.0 * mm;
    c.body_c = 66.0 * mm;
    c.length = 250.0 * mm;
    c.head_a = 28.0 * mm;
    c.head_b = 20.0 * mm;
    c.head_c = 18.0 * mm;
    c.neck_radius = 14.0 * mm;
    c.neck_root_x = -80.0 * mm;
    for (const Vec3& j : kTable51Joints) c.leg.joints.push_back(j * mm);
    const auto w = calibrated_widths_table_5_1();
    c.leg.limbs = {bar(w[0], 20.0 * mm), {w[1], 10.0 * mm, 20.0 * mm}, bar(w[2], 10.0 * mm)};
    c.leg.hinges = {{5.7 * mm, 3.0 * mm, 10.0 * mm}, {10.0 * mm, 3.0 * mm, 10.0 * mm}};
    c.leg.hip = {{9.85 * mm, 7.52 * mm, 5.93 * mm, true}, {13.0 * mm, 4.76 * mm, 5.0 * mm, false}};
    c.leg.pocket_gap = 1.0 * mm;
    c.mass = 1.69;
    return c;
}

Chicken table_5_3_chicken() {
    const Chicken a = table_5_1_chicken();
    Chicken c = a;
    c.name = "Table 5-3 (shackle rotating/inverting, L = 371.5 mm)";
    c.body_c = 65.0 * mm;  // width 130 mm
    c.length = 371.5 * mm;
    // J1 - L1 (75 mm at theta1 = 14 deg from +x) - J2 - L2 (70 mm, included angle theta2 = 35 deg) - J3,
    // J3 at Table 5-1's J3.
    const double l1 = 75.0 * mm, l2 = 70.0 * mm, theta1 = 14.0 * deg, theta2 = 35.0 * deg;
    const double phi2 = std::numbers::pi + theta1 - theta2;  // direction J2 -> J3
    const Vec3 j3 = a.leg.joints[2];
    const Vec3 j2 = j3 - l2 * Vec3(std::cos(phi2), std::sin(phi2), 0.0);
    const Vec3 j1 = j2 - l1 * Vec3(std::cos(theta1), std::sin(theta1), 0.0);
    // The hip bricks sit on the leg's inner face, as Table 5-1's J4 (z = 35 mm on a 10 mm deep L3):
    // with 30 mm deep limbs in the plane z = 40 mm that face is at z = 25 mm.
    c.leg.joints = {j1, j2, Vec3(j3.x(), j3.y(), j3.z() - 15.0 * mm)};
    c.leg.limbs = {bar(a.leg.limbs[0].width, 30.0 * mm), bar(a.leg.limbs[1].width, 30.0 * mm)};
    c.leg.hinges = {a.leg.hinges[0]};
    // Mesh quality [R] (the shackle model runs explicitly, so no feature may sit a fraction of a
    // millimetre from another): Table 5-1's parts put on this bird's 30 mm deep limbs left three
    // near-coincidences, each of which set the smallest element of the mesh in turn (scaled
    // Jacobian 0.002 -> 0.014 -> 0.021 -> 0.068, smallest altitude 0.005 -> 0.46 mm at the study's
    // 15 / 5 mm sizes):
    //  - the cross brick (13 mm) was 0.01 mm wider than L2 (12.99 mm): 1 mm narrower than L2 now,
    //    so its ends stay 1 mm inside the limb's sides and 2 mm from the groove's walls;
    //  - the J2 knuckle (10 mm deep) sat inside 30 mm deep limbs, its faces 0.0x mm proud of the
    //    thin L1 where they cross it: as deep as the limbs now (the hinge keeps its hole and ring);
    //  - the two bricks' 5.93 and 5 mm thicknesses put their faces 0.47 mm apart: both 5.93 mm.
    c.leg.hip[1].length = c.leg.limbs[1].width - 2.0 * mm;
    c.leg.hinges[0].depth = 30.0 * mm;
    c.leg.hip[1].thickness = c.leg.hip[0].thickness;
    return c;
}

void validate(const Chicken& c) {
    auto bad = [&](const std::string& what) { throw InputError("chicken '" + c.name + "': " + what); };
    for (double v : {c.body_a, c.body_b, c.body_c, c.length, c.head_a, c.head_b, c.head_c, c.neck_radius})
        if (!(v > 0.0) || !std::isfinite(v)) bad("body, head and neck sizes must be positive and finite");
    if (!(c.neck_root_x > -c.body_a && c.neck_root_x < c.body_a)) bad("the neck must start inside the body");
    if (!(c.head_center().x() < c.neck_root_x))
        bad(fmt::format("length {:.1f} mm puts the head centre behind the neck's root", c.length / mm));
    if (!(c.mass > 0.0)) bad("mass must be positive");
    const Leg& l = c.leg;
    if (l.joints.size() < 2) bad("the leg needs at least two joints");
    if (static_cast<int>(l.joints.size()) != l.limb_count() + 1) bad("the leg needs one limb per pair of joints");
    if (l.hinges.size() + 2 != l.joints.size()) bad("the leg needs one hinge per inner joint");
    if (!(l.pocket_gap > 0.0)) bad("pocket_gap must be positive");
    for (int i = 0; i < l.limb_count(); ++i) {
        const Limb& b = l.limbs[i];
        if (!(b.width > 0.0 && b.depth_lower > 0.0 && b.depth_upper > 0.0))
            bad(fmt::format("limb L{} needs a positive width and depths", i + 1));
        if (!(l.limb_length(i) > 0.0)) bad(fmt::format("limb L{} has zero length", i + 1));
        if (!(l.plane_z() - 0.5 * std::max(b.depth_lower, b.depth_upper) > 0.0))
            bad(fmt::format("limb L{} crosses the symmetry plane z = 0", i + 1));
    }
    for (std::size_t j = 0; j < l.hinges.size(); ++j) {
        const HoleHinge& h = l.hinges[j];
        if (!(h.hole_radius > 0.0 && h.neck > 0.0 && h.depth > 0.0))
            bad(fmt::format("hinge J{} needs a positive hole radius, neck and depth", j + 2));
    }
    for (const HipBrick& b : l.hip)
        if (!(b.length > 0.0 && b.height > 0.0 && b.thickness > 0.0)) bad("hip bricks need positive sizes");
}

MassProperties mass_properties(const Chicken& c, bool half) {
    validate(c);
    return with_model("chicken_mass_properties", [&] {
        const gmsh::vectorpair bird = bird_solid(c, half);
        occ::synchronize();
        return properties(bird);
    });
}

double volume(const Chicken& c, bool half) { return mass_properties(c, half).volume; }

double density_for_mass(const Chicken& c) { return density_for_mass(c, volume(c, false)); }
double density_for_mass(const Chicken& c, double full_volume) { return c.mass / full_volume; }

ElasticMaterial material(double density) { return ElasticMaterial::make("chicken", 6.1e6, 0.49, density); }

Mesh chicken_mesh(const Chicken& c, const MeshOptions& o) {
    validate(c);
    const std::string who = "chicken_mesh";
    return with_model(who, [&] {
        set_mesh_options(o.leg_size, o.body_size, o.order, who);
        gmsh::option::setNumber("Mesh.SecondOrderLinear", o.curved ? 0 : 1);
        const gmsh::vectorpair bird = bird_solid(c, o.half);
        const std::vector<int> volumes = volume_tags(bird);
        if (volumes.size() != 1)
            throw SolverError(fmt::format("{}: the bird did not fuse into one volume ({} volumes)", who, volumes.size()));
        const int centre = occ::addPoint(0, 0, 0);
        const Vec3 h = c.head_center();
        const int head = occ::addPoint(h.x(), h.y(), h.z());
        occ::synchronize();
        // The two reference points become mesh nodes: inside the volume (full model) or on the
        // symmetry face (half model), whichever holds them.
        if (!o.half) {
            gmsh::model::mesh::embed(0, {centre, head}, 3, volumes[0]);
        } else {
            gmsh::vectorpair faces;
            // (OpenCASCADE's boxes of the B-spline ellipsoid's cut are a few um loose.)
            gmsh::model::getEntitiesInBoundingBox(-kBig, -kBig, -1e-4, kBig, kBig, 1e-4, faces, 2);
            for (const auto& [pt, where] : {std::pair{centre, Vec3(0, 0, 0)}, std::pair{head, h}}) {
                bool done = false;
                for (const auto& [d, f] : faces) {
                    std::vector<double> closest, param;
                    gmsh::model::getClosestPoint(2, f, {where.x(), where.y(), where.z()}, closest, param);
                    if ((Vec3(closest[0], closest[1], closest[2]) - where).norm() < 1e-7) {
                        gmsh::model::mesh::embed(0, {pt}, 2, f);
                        done = true;
                        break;
                    }
                }
                if (!done) throw SolverError(who + ": a reference point is not on the symmetry face");
            }
        }
        gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, volumes), o.part);
        // Finer elements near the leg: a size growing with the distance from the leg's surfaces
        // and its groove's walls (every surface that lies within the leg's reach), from leg_size on
        // them to body_size two body sizes away.
        gmsh::vectorpair near_leg;
        {
            double x0 = kBig, x1 = -kBig, y0 = kBig, y1 = -kBig, reach = 0.0;
            for (const Vec3& p : c.leg.joints) {
                x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x());
                y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
            }
            for (const Limb& l : c.leg.limbs) reach = std::max(reach, l.width);
            for (const HoleHinge& h : c.leg.hinges) reach = std::max(reach, h.hole_radius + h.neck);
            for (const HipBrick& b : c.leg.hip) reach = std::max(reach, b.length);
            reach += 2.0 * c.leg.pocket_gap;
            const double zin = c.leg.plane_z() - reach;
            for (int side : {+1, -1}) {
                if (o.half && side < 0) continue;
                const double z0 = side > 0 ? zin : -kBig, z1 = side > 0 ? kBig : -zin;
                gmsh::vectorpair found;
                gmsh::model::getEntitiesInBoundingBox(x0 - reach, y0 - reach, z0, x1 + reach, y1 + reach, z1, found, 2);
                near_leg.insert(near_leg.end(), found.begin(), found.end());
            }
        }
        if (near_leg.empty()) throw SolverError(who + ": found no surface of the leg");
        std::vector<double> faces;
        for (const auto& [d, t] : near_leg) faces.push_back(t);
        const int distance = gmsh::model::mesh::field::add("Distance");
        gmsh::model::mesh::field::setNumbers(distance, "FacesList", faces);
        gmsh::model::mesh::field::setNumber(distance, "NumPointsPerCurve", 60);
        const int threshold = gmsh::model::mesh::field::add("Threshold");
        gmsh::model::mesh::field::setNumber(threshold, "IField", distance);
        gmsh::model::mesh::field::setNumber(threshold, "LcMin", o.leg_size);
        gmsh::model::mesh::field::setNumber(threshold, "LcMax", o.body_size);
        gmsh::model::mesh::field::setNumber(threshold, "DistMin", o.leg_size);
        gmsh::model::mesh::field::setNumber(threshold, "DistMax", 2.0 * o.body_size);
        gmsh::model::mesh::field::setAsBackgroundMesh(threshold);
        gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
        generate(o.order, who);
        Mesh m = mesh_from_gmsh_model(who);
        validate(m);
        // Gmsh numbers the mid-edge nodes after every corner node: each tet10 would reach two
        // distant parts of the nodal arrays every explicit cycle (mesh_tools.hpp, "node order").
        renumber_nodes(m, reverse_cuthill_mckee(m));

        const double tol = 1e-6;
        m.node_sets["body_center"] = {node_at(m, Vec3(0, 0, 0), tol, "body centre")};
        m.node_sets["head"] = {node_at(m, h, tol, "head centre")};
        if (o.half) m.node_sets["symmetry"] = m.select_nodes([&](const Vec3& x) { return std::abs(x.z()) < tol; });
        const Leg& leg = c.leg;
        const double angle = leg.limb_angle(0), reach = 0.5 * std::hypot(leg.limbs[0].width, std::max(leg.limbs[0].depth_lower, leg.limbs[0].depth_upper)) + tol;
        std::vector<int> paw;
        for (int side : {+1, -1}) {
            if (o.half && side < 0) continue;
            const Vec3 p = mirrored(Vec3(leg.joints[0].x(), leg.joints[0].y(), leg.plane_z()), side);
            for (int n : nodes_on_plane(m, p, Vec3(std::cos(angle), std::sin(angle), 0.0), reach, tol)) paw.push_back(n);
        }
        if (paw.empty()) throw SolverError(who + ": no node on the paw face");
        std::sort(paw.begin(), paw.end());
        m.node_sets["paw"] = paw;
        return m;
    });
}

void place(Mesh& mesh, const Vec3& centroid, double theta) {
    const double c = std::cos(theta), s = std::sin(theta);
    for (Vec3& x : mesh.nodes) x = Vec3(c * x.x() - s * x.y(), s * x.x() + c * x.y(), x.z()) + centroid;
}

double theta_b(const Vec3& head, const Vec3& body_center) {
    const Vec3 d = body_center - head;
    return std::atan2(d.y(), d.x());
}

MassProperties limb_mass_properties(const Chicken& c, int limb) {
    validate(c);
    if (limb < 1 || limb > c.leg.limb_count())
        throw InputError(fmt::format("limb_mass_properties: limb {} does not exist (the leg has {})", limb, c.leg.limb_count()));
    return with_model("limb_mass_properties", [&] {
        const gmsh::vectorpair v = limb_solid(c.leg, limb - 1);
        occ::synchronize();
        return properties(v);
    });
}

Mesh limb_mesh(const Chicken& c, int limb, const LimbMeshOptions& o) {
    validate(c);
    const Leg& leg = c.leg;
    if (limb < 1 || limb > leg.limb_count())
        throw InputError(fmt::format("limb_mesh: limb {} does not exist (the leg has {})", limb, leg.limb_count()));
    const std::string who = fmt::format("limb_mesh(L{})", limb);
    return with_model(who, [&] {
        set_mesh_options(o.size, o.size, o.order, who);
        const std::vector<int> volumes = volume_tags(limb_solid(leg, limb - 1));
        occ::synchronize();
        gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, volumes), o.part);
        generate(o.order, who);
        Mesh m = mesh_from_gmsh_model(who);
        validate(m);
        // Fixed at the upper joint J(i+1), loaded at the lower joint J(i): through the hole of a
        // hinge joint, through the limb's end face otherwise.
        const int i = limb - 1;
        const double tol = 1e-6, angle = leg.limb_angle(i);
        const Vec3 dir(std::cos(angle), std::sin(angle), 0.0);
        const Limb& b = leg.limbs[i];
        auto joint_nodes = [&](int j, double depth) {
            const Vec3 p(leg.joints[j].x(), leg.joints[j].y(), leg.plane_z());
            if (j >= 1 && j + 1 < static_cast<int>(leg.joints.size()))
                return nodes_on_bore(m, p, leg.hinges[j - 1].hole_radius, 0.5 * kBig, 1e-3 * leg.hinges[j - 1].hole_radius);
            return nodes_on_plane(m, p, dir, 0.5 * std::hypot(b.width, depth) + tol, tol);
        };
        m.node_sets["fixed"] = joint_nodes(i + 1, b.depth_upper);
        m.node_sets["loaded"] = joint_nodes(i, b.depth_lower);
        if (m.node_sets["fixed"].empty() || m.node_sets["loaded"].empty())
            throw SolverError(who + ": no node at a joint of the limb");
        return m;
    });
}

}  // namespace fem::chicken

