#include "hand/hand.hpp"

#include <cmath>
#include <numbers>
#include <set>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fem::hand {

using units::deg;
using units::inch;

std::vector<FingerRow> table_4_1() {
    // Table 4-1: length, h_f, theta_f, r_drum, R_x, R_z, alpha (alpha from Table 3-3 by length).
    return {
        {"A", 4.5 * inch, 3.0 * inch, -11.25 * deg, 3.25 * inch, 45.0 * deg, 10.0 * deg, 180.0},
        {"B", 4.5 * inch, 3.0 * inch, 11.25 * deg, 3.25 * inch, -45.0 * deg, 10.0 * deg, 180.0},
        {"C", 3.0 * inch, 1.0 * inch, -22.5 * deg, 4.25 * inch, -45.0 * deg, -2.5 * deg, 600.0},
        {"D", 3.0 * inch, 0.75 * inch, 0.0, 4.25 * inch, 0.0, -10.0 * deg, 600.0},
        {"E", 3.0 * inch, 1.0 * inch, 22.5 * deg, 4.25 * inch, 45.0 * deg, -2.5 * deg, 600.0},
    };
}

RigidMotion Drum::motion() const {
    // About -y: on the object side (+z) the drum surface moves in -x.
    return RigidMotion::rotation(centre, -Vec3::UnitY(), omega);
}

Drum stepped_drum(double omega) {
    Drum d;
    d.levels = {{0.0, 2.0 * inch, 4.25 * inch}, {2.0 * inch, 4.0 * inch, 3.25 * inch}};
    d.omega = Curve::constant(omega);
    return d;
}

int finger_layers(const FingerMesh& m, double length) {
    return std::max(1, static_cast<int>(std::ceil(length / m.layer_length - 1e-9)));
}

void validate(const HandSpec& h) {
    if (h.drum.levels.empty()) throw InputError("hand: the drum has no levels");
    for (std::size_t i = 0; i < h.drum.levels.size(); ++i) {
        const auto& l = h.drum.levels[i];
        if (!(l.radius > 0.0) || !(l.y_top > l.y_bottom))
            throw InputError(fmt::format("hand: drum level {} needs radius > 0 and y_top > y_bottom (got r = {}, y {}..{})",
                                         i, l.radius, l.y_bottom, l.y_top));
    }
    if (h.fingers.empty()) throw InputError("hand: no fingers");
    std::set<std::string> names;
    for (const auto& f : h.fingers) {
        if (f.name.empty() || !names.insert(f.name).second)
            throw InputError(fmt::format("hand: finger names must be unique and non-empty (finger '{}')", f.name));
        if (!(f.length > 0.0) || !(f.drum_radius > 0.0) || !(f.alpha >= 0.0) || !std::isfinite(f.root_height) ||
            !std::isfinite(f.initial_angle) || !std::isfinite(f.roll) || !std::isfinite(f.pitch))
            throw InputError(fmt::format("hand: finger '{}' needs length > 0, drum_radius > 0, alpha >= 0 and finite angles "
                                         "(got L = {}, r = {}, alpha = {})", f.name, f.length, f.drum_radius, f.alpha));
    }
    if (h.mesh.section < 1 || !(h.mesh.layer_length > 0.0) || !(h.mesh.semi_major > 0.0) || !(h.mesh.semi_minor > 0.0))
        throw InputError("hand: finger mesh needs section >= 1, layer_length > 0 and positive semi-axes");
    if (std::abs(std::abs(h.theta_sign) - 1.0) > 0.0 || std::abs(std::abs(h.roll_sign) - 1.0) > 0.0)
        throw InputError("hand: theta_sign and roll_sign must be +1 or -1");
}

namespace {
Mat3 axis_rotation(const Vec3& axis, double angle) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }
}  // namespace

Placement place_finger(const HandSpec& h, const FingerRow& f) {
    Placement p;
    p.angle = h.drum.initial_angle + h.theta_sign * f.initial_angle;
    const double s = std::sin(p.angle), c = std::cos(p.angle);
    const Vec3 er(s, 0.0, -c), et(c, 0.0, s), ey = Vec3::UnitY();
    // Mesh frame (major x, minor y, axis z) -> unrolled local frame: major along y', minor along
    // z' = e_t, axis along x' = e_r (columns: images of the mesh axes; right-handed: y' x e_t = e_r).
    Mat3 base;
    base.col(0) = ey, base.col(1) = et, base.col(2) = er;
    // Roll about the finger axis, then pitch about the tangential axis (+ lifts the tip: e_r -> y).
    const Mat3 roll = axis_rotation(er, h.roll_sign * f.roll);
    const Mat3 pitch = axis_rotation(et, f.pitch);
    p.rotation = pitch * roll * base;
    p.root = h.drum.centre + f.drum_radius * er + f.root_height * ey;
    return p;
}

Mesh hand_mesh(const HandSpec& h) {
    validate(h);
    Mesh all;
    for (const auto& f : h.fingers) {
        const finger::EllipticCylinder g{h.mesh.semi_major, h.mesh.semi_minor, f.length};
        Mesh m = finger::hex_finger(g, finger::mapped_cross_section(h.mesh.section), finger_layers(h.mesh, f.length),
                                    "finger-" + f.name);
        const Placement p = place_finger(h, f);
        for (auto& x : m.nodes) x = p.root + p.rotation * x;
        std::map<std::string, std::vector<int>> sets;
        sets["root-" + f.name] = m.node_set("root");
        sets["tip-" + f.name] = m.node_set("tip");
        sets["tip-centre-" + f.name] = m.node_set("tip_center");
        m.node_sets = std::move(sets);
        all.append(m);
    }
    return all;
}

Mesh drum_mesh(const Drum& drum, int n) {
    if (n < 3) throw InputError(fmt::format("drum mesh: needs at least 3 segments around (got {})", n));
    Mesh m;
    ElementBlock b{"drum", ElementShape::Quad4, {}};
    for (const auto& l : drum.levels) {
        const int base = static_cast<int>(m.nodes.size());
        for (int i = 0; i < n; ++i) {
            const double phi = 2.0 * std::numbers::pi * i / n;
            const Vec3 er(std::sin(phi), 0.0, -std::cos(phi));
            m.nodes.push_back(drum.centre + l.radius * er + l.y_bottom * Vec3::UnitY());
            m.nodes.push_back(drum.centre + l.radius * er + l.y_top * Vec3::UnitY());
        }
        for (int i = 0; i < n; ++i) {
            const int j = (i + 1) % n;
            // bottom_i, top_i, top_j, bottom_j: normal y x e_t = e_r (outward).
            for (int k : {base + 2 * i, base + 2 * i + 1, base + 2 * j + 1, base + 2 * j}) b.connectivity.push_back(k);
        }
    }
    m.blocks.push_back(std::move(b));
    return m;
}

}  // namespace fem::hand
