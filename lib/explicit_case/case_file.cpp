// Reading the explicit case file (case_file.hpp; every key: CASE_FILE.md). Reading checks types,
// ranges, names and cross-references (materials, parts, rigid parts in contact pairs and boundary
// conditions); it never opens a mesh file (CaseModel does).
#include "explicit_case/case_file.hpp"

#include <algorithm>
#include <set>
#include <tuple>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "core/units.hpp"
#include "input/numbers.hpp"
#include "input/toml_input.hpp"

namespace fem::explicit_case {
namespace {

using input::Range;
using input::TomlTable;

Vec3 vec3(const TomlTable& t, std::string_view key, Range range = Range::any()) {
    const auto v = t.reals(key, 3, range);
    return {v[0], v[1], v[2]};
}
Vec3 vec3_or(const TomlTable& t, std::string_view key, const Vec3& fallback) {
    return t.has(key) ? vec3(t, key) : fallback;
}

// A time curve (explicit/curve.hpp) from one of three keys: `<key>` a number (constant), `<key>_curve`
// points [[t, y], ...] (linear between them, a repeated t is a step), `<key>_steps` [[t, y], ...]
// (y from t until the next t). Absent: `fallback`.
Curve curve(const TomlTable& t, const std::string& key, Curve fallback) {
    const std::string points = key + "_curve", steps = key + "_steps";
    const int given = t.has(key) + t.has(points) + t.has(steps);
    if (given > 1) t.fail(key, fmt::format("give one of {}, {} and {}", key, points, steps));
    if (t.has(key)) return Curve::constant(t.real(key));
    if (given == 0) return fallback;
    const std::string& which = t.has(points) ? points : steps;
    std::vector<std::pair<double, double>> p;
    for (const auto& row : t.matrix(which, 2)) p.emplace_back(row[0], row[1]);
    const std::string name = t.name().empty() ? which : t.name() + "." + which;
    try {
        return which == points ? Curve(std::move(p), name) : Curve::steps(p, name);
    } catch (const InputError& e) {
        t.fail(which, e.what());  // the curve's own complaint (times not increasing), with the line
    }
}

unsigned dof_mask(const TomlTable& t, std::string_view key) {
    unsigned m = 0;
    for (const auto& d : t.choices(key, {"x", "y", "z", "rx", "ry", "rz", "all"})) {
        if (d == "all") m |= Dofs::all().mask;
        else if (d == "x") m |= Dofs::x;
        else if (d == "y") m |= Dofs::y;
        else if (d == "z") m |= Dofs::z;
        else if (d == "rx") m |= Dofs::rx;
        else if (d == "ry") m |= Dofs::ry;
        else m |= Dofs::rz;
    }
    if (m == 0) t.fail(key, "must name at least one DOF (x y z rx ry rz all)");
    return m;
}

std::array<int, 3> three_counts(const TomlTable& t, std::string_view key) {
    const auto n = t.integers<int>(key, 3, {.min = 1, .max = 100000});
    return {n[0], n[1], n[2]};
}

// The keys of a table depend on its `mesh`: the first key (in file order) outside `keys` is refused,
// naming the keys that kind takes (a key of another kind is not silently ignored).
void refuse_keys_outside(const TomlTable& t, const std::vector<std::string>& keys, const std::string& kind) {
    std::string first;
    for (const auto& k : t.keys())
        if (std::find(keys.begin(), keys.end(), k) == keys.end() && (first.empty() || t.where(k).line < t.where(first).line))
            first = k;
    if (!first.empty())
        t.fail(first, fmt::format("is not a key of {}{} (keys: {})", kind, input::did_you_mean(first, keys), input::one_of(keys)));
}

// Refuses a mesh request that cannot fit before anything is allocated (core/memory.hpp): about
// 2 kB per element for the mesh, the element group and the nodal state.
void require_room(const TomlTable& t, std::string_view key, double elements, const std::string& what) {
    try {
        require_memory(elements * 2048.0, what);
    } catch (const InputError& e) {
        t.fail(key, e.what());
    }
}

// A stepped drum's `levels` = [[y_bottom, y_top, radius], ...] (hand::DrumLevel).
std::vector<hand::DrumLevel> drum_levels(const TomlTable& t) {
    std::vector<hand::DrumLevel> levels;
    for (const auto& row : t.matrix("levels", 3)) {
        if (!(row[1] > row[0]) || !(row[2] > 0))
            t.fail("levels", fmt::format("each level is [y_bottom, y_top, radius] with y_top > y_bottom and radius > 0, got "
                                         "[{}, {}, {}]",
                                         row[0], row[1], row[2]));
        levels.push_back({row[0], row[1], row[2]});
    }
    return levels;
}

int line_of(const TomlTable& t) { return t.where().line; }

[[noreturn]] void unknown_name(const TomlTable& t, std::string_view key, const std::string& name, std::string_view what,
                               const std::vector<std::string>& known) {
    t.fail(key, fmt::format("'{}' is not {}{}", name, what,
                            known.empty() ? std::string() : input::did_you_mean(name, known) + " (known: " + input::one_of(known) + ")"));
}

ElasticMaterial material_of(const TomlTable& t, const std::map<std::string, ElasticMaterial>& materials) {
    const std::string name = t.string("material");
    auto it = materials.find(name);
    if (it == materials.end()) {
        std::vector<std::string> known;
        for (const auto& [n, m] : materials) known.push_back(n);
        unknown_name(t, "material", name, "a [[material]]", known);
    }
    return it->second;
}

Part read_part(const TomlTable& t, const std::map<std::string, ElasticMaterial>& materials, bool hand_case) {
    Part p;
    p.line = line_of(t);
    p.name = t.string("name");
    p.mesh = t.choice("mesh", {"box", "finger", "ellipsoid", "gmsh", "deck"});
    if (hand_case && p.mesh == "finger")
        t.fail("mesh", "a case with [hand] has its fingers in [hand]; its [[part]]s are the objects it grasps (ellipsoid, "
                       "box, gmsh or deck), got 'finger'");
    std::vector<std::string> keys{"name", "mesh", "material", "alpha", "damping_frame", "initial_velocity"};
    if (p.mesh != "ellipsoid") keys.insert(keys.end(), {"offset", "hourglass_qm", "bulk_quadratic", "bulk_linear"});
    if (hand_case && p.mesh != "ellipsoid") keys.push_back("symmetry_set");
    if (p.mesh == "box") keys.insert(keys.end(), {"size", "origin", "elements", "element"});
    if (p.mesh == "finger") keys.insert(keys.end(), {"table_3_2_case", "table_4_1_finger"});
    if (p.mesh == "ellipsoid")
        keys.insert(keys.end(), {"semi_axes", "centre", "grid", "inner_scale", "half", "mass", "carried_velocity", "carried_scale",
                                 "carried_scale_curve", "carried_scale_steps"});
    if (p.mesh == "gmsh" || p.mesh == "deck") keys.push_back("file");
    refuse_keys_outside(t, keys, fmt::format("a '{}' part", p.mesh));
    p.material = material_of(t, materials);
    p.alpha = t.real_or("alpha", 0.0, Range::non_negative());
    if (t.has("damping_frame")) {
        if (hand_case)
            t.fail("damping_frame", "a case with [hand] damps its objects on absolute velocity ([hand] damping_frame is the fingers')");
        p.damping_frame = t.string("damping_frame");
        if (!(p.alpha > 0.0)) t.fail("damping_frame", "needs alpha > 0 (it names what the part's alpha damping is relative to)");
    }
    p.initial_velocity = vec3_or(t, "initial_velocity", Vec3::Zero());
    if (p.mesh != "ellipsoid") {
        p.offset = vec3_or(t, "offset", Vec3::Zero());
        p.hourglass_qm = t.real_or("hourglass_qm", 0.1, Range::non_negative());
        p.bulk.quadratic = t.real_or("bulk_quadratic", BulkViscosity{}.quadratic, Range::non_negative());
        p.bulk.linear = t.real_or("bulk_linear", BulkViscosity{}.linear, Range::non_negative());
        if (hand_case) p.symmetry_set = t.string_or("symmetry_set", "");
    }
    if (p.mesh == "box") {
        p.size = vec3(t, "size", Range::positive());
        p.origin = vec3_or(t, "origin", Vec3::Zero());
        p.elements = three_counts(t, "elements");
        p.element = t.choice_or("element", {"hex8", "tet4", "tet10"}, "hex8");
        const double n = double(p.elements[0]) * p.elements[1] * p.elements[2] * (p.element == "hex8" ? 1 : 6);
        require_room(t, "elements", n, fmt::format("a {} x {} x {} {} box", p.elements[0], p.elements[1], p.elements[2], p.element));
    } else if (p.mesh == "finger") {
        if (t.has("table_3_2_case") == t.has("table_4_1_finger"))
            t.fail("give exactly one of table_3_2_case (\"A\"..\"D\") and table_4_1_finger (\"A\"..\"E\")");
        if (t.has("table_3_2_case")) p.table_3_2_case = t.choice("table_3_2_case", {"A", "B", "C", "D"});
        else p.table_4_1_finger = t.choice("table_4_1_finger", {"A", "B", "C", "D", "E"});
    } else if (p.mesh == "ellipsoid") {
        hand::EllipsoidObject& o = p.ellipsoid;
        o.part = p.name;
        o.material = p.material;
        o.alpha = p.alpha;
        o.initial_velocity = p.initial_velocity;
        o.semi_axes = vec3(t, "semi_axes", Range::positive());
        o.centre = vec3_or(t, "centre", Vec3::Zero());
        if (t.has("grid")) {
            const auto g = t.integers<int>("grid", 4, {.min = 1, .max = 1000});
            o.grid.nx = g[0], o.grid.ny = g[1], o.grid.nz = g[2], o.grid.layers = g[3];
            const double n = double(g[0]) * g[1] * g[2] + 2.0 * (double(g[0]) * g[1] + double(g[1]) * g[2] + double(g[0]) * g[2]) * g[3];
            require_room(t, "grid", n, fmt::format("an ellipsoid grid [{}, {}, {}, {}]", g[0], g[1], g[2], g[3]));
        }
        // The inner block's corners must stay inside the ellipsoid (s sqrt(3) < 1).
        o.grid.inner_scale = t.real_or("inner_scale", o.grid.inner_scale, Range::open(0.0, 0.57));
        o.half = t.boolean_or("half", false);
        o.mass = t.real_or("mass", 0.0, Range::positive());
        // Carried by the conveyor (hand::EllipsoidObject::carried_velocity: Sec 4.4's "conveyor speed
        // = object speed"): the velocity components along its non-zero axes prescribed, times a curve.
        const bool scaled = t.has("carried_scale") || t.has("carried_scale_curve") || t.has("carried_scale_steps");
        if (t.has("carried_velocity")) {
            if (!hand_case)
                t.fail("carried_velocity", "only the objects of a case with [hand] are carried (elsewhere a [[boundary]] "
                                           "velocity prescribes a node set's velocity)");
            o.carried_velocity = vec3(t, "carried_velocity");
            if (o.carried_velocity == Vec3::Zero()) t.fail("carried_velocity", "is zero: it would carry nothing; remove it");
            o.carried_scale = curve(t, "carried_scale", Curve());
        } else if (scaled) {
            t.fail(t.has("carried_scale") ? "carried_scale" : t.has("carried_scale_curve") ? "carried_scale_curve" : "carried_scale_steps",
                   "scales carried_velocity, which is not given");
        }
    } else {
        p.file = t.path("file");
    }
    return p;
}

RigidPart read_rigid_part(const TomlTable& t, bool hand_case) {
    RigidPart r;
    r.line = line_of(t);
    r.name = t.string("name");
    r.mesh = t.choice("mesh", {"plate", "box", "drum", "gmsh"});
    if (hand_case && r.mesh != "plate")
        t.fail("mesh", fmt::format("a case with [hand] takes translating plates as its rigid parts (the drum is the "
                                   "hand's), got '{}'",
                                   r.mesh));
    std::vector<std::string> keys{"name", "mesh", "depth", "track_approach_side", "motion"};
    if (r.mesh == "plate") keys.insert(keys.end(), {"centre", "u", "v", "segments"});
    if (r.mesh == "box") keys.insert(keys.end(), {"size", "origin", "elements"});
    if (r.mesh == "drum") keys.insert(keys.end(), {"centre", "levels", "segments"});
    if (r.mesh == "gmsh") keys.push_back("file");
    refuse_keys_outside(t, keys, fmt::format("a '{}' rigid part", r.mesh));
    r.depth = t.real_or("depth", 0.03, Range::positive());
    r.track_approach_side = t.boolean_or("track_approach_side", false);
    if (r.mesh == "plate") {
        hand::Plate& q = r.plate;
        q.part = r.name;
        q.depth = r.depth;
        q.track_approach_side = r.track_approach_side;
        q.centre = vec3(t, "centre");
        q.u = vec3(t, "u");
        q.v = vec3(t, "v");
        if (q.u.cross(q.v).norm() <= 1e-12 * (q.u.norm() * q.v.norm() + 1e-300))
            t.fail("v", "u and v must span a plane (not parallel, not zero)");
        const auto s = t.integers<int>("segments", 2, {.min = 1, .max = 100000});
        q.nu = s[0], q.nv = s[1];
        require_room(t, "segments", double(s[0]) * s[1], fmt::format("a {} x {} plate", s[0], s[1]));
    } else if (r.mesh == "box") {
        r.size = vec3(t, "size", Range::positive());
        r.origin = vec3_or(t, "origin", Vec3::Zero());
        r.elements = three_counts(t, "elements");
        require_room(t, "elements", double(r.elements[0]) * r.elements[1] * r.elements[2],
                     fmt::format("a {} x {} x {} box", r.elements[0], r.elements[1], r.elements[2]));
    } else if (r.mesh == "drum") {
        r.centre = vec3_or(t, "centre", Vec3::Zero());
        r.levels = drum_levels(t);
        r.drum_segments = t.integer_or<int>("segments", 48, {.min = 3, .max = 100000});
    } else {
        r.file = t.path("file");
    }
    int motions = 0;
    std::optional<std::pair<Vec3, Curve>> translation;  // the first entry, when a translation
    for (const TomlTable& m : t.tables("motion")) {
        const std::string type = m.choice("type", {"translation", "rotation"});
        RigidMotion e;
        if (type == "translation") {
            m.allow({"type", "direction", "speed", "speed_curve", "speed_steps"});
            const Vec3 direction = vec3(m, "direction");
            if (direction.norm() == 0.0) m.fail("direction", "must not be zero");
            Curve speed = curve(m, "speed", Curve::constant(1.0));
            if (motions == 0) translation = std::pair{direction, speed};
            e = RigidMotion::translation(direction, std::move(speed));
        } else {
            m.allow({"type", "point", "axis", "omega", "omega_curve", "omega_steps"});
            const Vec3 axis = vec3(m, "axis");
            if (axis.norm() == 0.0) m.fail("axis", "must not be zero");
            if (!m.has("omega") && !m.has("omega_curve") && !m.has("omega_steps"))
                m.fail("missing the angular speed: omega [rad/s], omega_curve or omega_steps");
            e = RigidMotion::rotation(vec3_or(m, "point", Vec3::Zero()), axis, curve(m, "omega", Curve::constant(0.0)));
        }
        r.motion = r.motion.then(e);  // later entries act on the result of the earlier ones
        ++motions;
    }
    if (hand_case && motions > 0 && !(motions == 1 && translation))
        t.fail("motion", "a plate of a case with [hand] moves by one translation (one [[rigid_part.motion]] of type "
                         "\"translation\")");
    if (motions == 1 && translation) std::tie(r.plate.direction, r.plate.speed) = *translation;
    return r;
}

hand::FingerRow read_finger(const TomlTable& t) {
    t.allow({"name", "length", "root_height", "initial_angle_deg", "drum_radius", "roll_deg", "pitch_deg", "alpha"});
    hand::FingerRow f;
    f.name = t.string("name");
    f.length = t.real("length", Range::positive());
    f.root_height = t.real("root_height");
    f.initial_angle = t.real("initial_angle_deg", Range::closed(-360, 360)) * units::deg;
    f.drum_radius = t.real("drum_radius", Range::positive());
    f.roll = t.real_or("roll_deg", 0.0, Range::closed(-360, 360)) * units::deg;
    f.pitch = t.real_or("pitch_deg", 0.0, Range::closed(-90, 90)) * units::deg;
    f.alpha = t.real_or("alpha", 0.0, Range::non_negative());
    return f;
}

// [hand.turn]: the whole hand turned about an axis on top of the drum's spin (hand::HandTurn: the
// flip of Sec 4.4, Table 4-6).
hand::HandTurn read_turn(const TomlTable& t) {
    t.allow({"point", "axis", "omega", "omega_curve", "omega_steps"});
    hand::HandTurn turn;
    turn.point = vec3_or(t, "point", Vec3::Zero());
    turn.axis = vec3_or(t, "axis", Vec3::UnitZ());
    if (turn.axis == Vec3::Zero()) t.fail("axis", "must not be zero");
    if (!t.has("omega") && !t.has("omega_curve") && !t.has("omega_steps"))
        t.fail("missing the angular speed: omega [rad/s], omega_curve or omega_steps");
    turn.omega = curve(t, "omega", Curve::constant(0.0));
    return turn;
}

hand::Scene read_hand(const TomlTable& t, const std::map<std::string, ElasticMaterial>& materials) {
    t.allow({"fingers", "finger", "drum", "turn", "material", "section", "layer_length", "semi_major", "semi_minor", "theta_sign",
             "roll_sign", "damping_frame", "fingers_start_spinning", "symmetry", "mirror_contact"});
    hand::Scene h;
    hand::HandSpec& s = h.hand;
    if (t.has("fingers") == !t.tables("finger").empty())
        t.fail("give the fingers either as fingers = \"table-4-1\" or as [[hand.finger]] rows");
    if (t.has("fingers")) {
        t.choice("fingers", {"table-4-1"});
        s.fingers = hand::table_4_1();
    } else {
        s.fingers.clear();
        std::set<std::string> names;
        for (const TomlTable& f : t.tables("finger")) {
            s.fingers.push_back(read_finger(f));
            if (!names.insert(s.fingers.back().name).second) f.fail("name", "'" + s.fingers.back().name + "' is used twice");
        }
    }
    if (t.has("material")) s.rubber = material_of(t, materials);
    s.mesh.section = t.integer_or<int>("section", s.mesh.section, {.min = 1, .max = 100});
    s.mesh.layer_length = t.real_or("layer_length", s.mesh.layer_length, Range::positive());
    s.mesh.semi_major = t.real_or("semi_major", s.mesh.semi_major, Range::positive());
    s.mesh.semi_minor = t.real_or("semi_minor", s.mesh.semi_minor, Range::positive());
    s.theta_sign = t.integer_or<int>("theta_sign", -1, {.min = -1, .max = 1});
    s.roll_sign = t.integer_or<int>("roll_sign", 1, {.min = -1, .max = 1});
    if (s.theta_sign == 0) t.fail("theta_sign", "must be -1 or 1, got 0");
    if (s.roll_sign == 0) t.fail("roll_sign", "must be -1 or 1, got 0");
    h.damping_frame = t.choice_or("damping_frame", {"absolute", "drum"}, "absolute") == "drum" ? hand::DampingFrame::drum
                                                                                              : hand::DampingFrame::absolute;
    h.fingers_start_spinning = t.boolean_or("fingers_start_spinning", true);
    h.symmetry = t.boolean_or("symmetry", true);
    h.mirror_contact = t.boolean_or("mirror_contact", false);
    if (h.mirror_contact && !h.symmetry) t.fail("mirror_contact", "needs symmetry = true (the mirror images are across the symmetry plane)");
    if (const auto d = t.optional_table("drum")) {
        d->allow({"centre", "levels", "omega", "omega_curve", "omega_steps", "initial_angle_deg", "segments"});
        s.drum.centre = vec3_or(*d, "centre", Vec3::Zero());
        if (d->has("levels")) {
            s.drum.levels = drum_levels(*d);
        }
        s.drum.omega = curve(*d, "omega", s.drum.omega);
        s.drum.initial_angle = d->real_or("initial_angle_deg", 0.0) * units::deg;
        h.drum_segments = d->integer_or<int>("segments", 48, {.min = 3, .max = 100000});
    }
    if (const auto turn = t.optional_table("turn")) h.turn = read_turn(*turn);
    try {
        hand::validate(s);
    } catch (const InputError& e) {
        t.fail(e.what());
    }
    return h;
}

Contact read_contact(const TomlTable& t) {
    t.allow({"slave", "master", "mu_s", "mu_d", "decay", "two_way", "penalty_scale"});
    Contact c;
    c.line = line_of(t);
    c.slave = t.string("slave");
    c.master = t.string("master");
    if (c.slave == c.master) t.fail("master", "is the slave part too: a part against itself (self contact) is not supported");
    c.friction.mu_static = t.real_or("mu_s", 0.0, Range::non_negative());
    c.friction.mu_dynamic = t.real_or("mu_d", c.friction.mu_static, Range::non_negative());
    c.friction.decay = t.real_or("decay", 0.0, Range::non_negative());
    c.two_way = t.boolean_or("two_way", true);
    c.penalty_scale = t.real_or("penalty_scale", 0.1, Range::positive());
    return c;
}

Boundary read_boundary(const TomlTable& t) {
    t.allow({"set", "fix", "velocity", "velocity_curve", "velocity_steps", "displacement", "scale", "scale_curve",
             "scale_steps", "symmetry", "point", "follow"});
    Boundary b;
    b.line = line_of(t);
    const int kinds = t.has("fix") + t.has("velocity") + t.has("displacement") + t.has("symmetry") + t.has("follow");
    if (kinds != 1) t.fail("give exactly one of fix, velocity, displacement, symmetry and follow");
    if (t.has("symmetry")) {
        b.kind = Boundary::Kind::symmetry;
        const std::string axis = t.choice("symmetry", {"x", "y", "z"});
        b.normal = axis == "x" ? Vec3::UnitX() : axis == "y" ? Vec3::UnitY() : Vec3::UnitZ();
        if (t.has("set") == t.has("point")) t.fail("symmetry", "give the plane's nodes as a set or a point on the plane");
        if (t.has("point")) b.point = vec3(t, "point");
        else b.set = t.string("set");
        return b;
    }
    b.set = t.string("set");
    if (t.has("fix")) {
        b.kind = Boundary::Kind::fix;
        b.dofs = dof_mask(t, "fix");
    } else if (t.has("follow")) {
        b.kind = Boundary::Kind::follow;
        b.rigid_part = t.string("follow");
    } else {
        b.kind = t.has("velocity") ? Boundary::Kind::velocity : Boundary::Kind::displacement;
        b.value = vec3(t, b.kind == Boundary::Kind::velocity ? "velocity" : "displacement");
        b.curve = curve(t, "scale", Curve());
    }
    return b;
}

// [[phase]] name, start_time, release: the run in stages (ExplicitCase::phases).
void read_phases(const TomlTable& root, ExplicitCase& c) {
    const auto tables = root.tables("phase");
    std::set<std::string> names;
    for (std::size_t k = 0; k < tables.size(); ++k) {
        const TomlTable& t = tables[k];
        t.allow({"name", "start_time", "release"});
        Phase ph;
        ph.line = line_of(t);
        ph.name = t.string("name");
        if (ph.name.empty() || ph.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") != std::string::npos)
            t.fail("name", fmt::format("must be one word of letters, digits, _ and - (it names the phase's output folder), got '{}'", ph.name));
        if (!names.insert(ph.name).second) t.fail("name", "'" + ph.name + "' is used twice");
        if (k == 0) {
            if (t.has("start_time") && t.real("start_time") != 0.0) t.fail("start_time", "the first phase starts at 0 (the run's start)");
            if (t.has("release")) t.fail("release", "the first phase has nothing to release (objects are carried from t = 0)");
        } else {
            ph.start = t.real("start_time", Range::positive());
            if (!(ph.start > c.phases.back().start))
                t.fail("start_time", fmt::format("{} s is not after the previous phase's start ({} s)", ph.start, c.phases.back().start));
            if (!(ph.start < c.control.end_time))
                t.fail("start_time", fmt::format("{} s is not before end_time ({} s)", ph.start, c.control.end_time));
        }
        if (t.has("release")) {
            std::vector<std::string> carried;
            for (const Part& p : c.parts)
                if (p.mesh == "ellipsoid" && p.ellipsoid.carried_velocity != Vec3::Zero()) carried.push_back(p.name);
            for (const std::string& name : t.strings("release")) {
                if (std::find(carried.begin(), carried.end(), name) == carried.end())
                    unknown_name(t, "release", name, "a carried object (an ellipsoid part with carried_velocity)", carried);
                for (const Phase& before : c.phases)
                    if (std::find(before.release.begin(), before.release.end(), name) != before.release.end())
                        t.fail("release", fmt::format("'{}' is released already by phase '{}'", name, before.name));
                ph.release.push_back(name);
            }
        }
        c.phases.push_back(ph);
    }
    if (c.phases.size() == 1)
        tables[0].fail("a single [[phase]] is the whole run: give two or more phases, or none");
}

ExplicitCase from_document(const input::TomlDocument& doc) {
    const TomlTable root = doc.root();
    root.allow({"control", "output", "material", "part", "rigid_part", "hand", "contact", "rigid_wall", "boundary", "load", "gravity",
                "phase", "health_exemption"});
    ExplicitCase c;
    c.source = doc.source();
    c.base = doc.base();
    const std::string stem = std::filesystem::path(c.source).stem().string();

    const TomlTable control = root.table("control");
    control.allow({"end_time", "dt_scale", "threads", "restart_times", "restart_interval", "restart_from", "name"});
    c.control.end_time = control.real("end_time", Range::positive());
    c.control.dt_scale = control.real_or("dt_scale", 0.9, Range::left_open(0.0, 1.0));
    c.control.threads = control.integer_or<int>("threads", 0, {.min = 0, .max = 1024});
    if (control.has("restart_times")) {
        c.control.restart_times = control.reals("restart_times", 0, Range::positive());
        for (double t : c.control.restart_times)
            if (t >= c.control.end_time)
                control.fail("restart_times", fmt::format("{} s is not before end_time ({} s)", t, c.control.end_time));
    }
    c.control.restart_interval = control.real_or("restart_interval", 0.0, Range::positive());
    if (control.has("restart_from")) c.control.restart_from = control.path("restart_from");
    c.control.name = control.string_or("name", stem);
    if (c.control.name.empty()) control.fail("name", "must not be empty");

    c.output.folder = c.base / (stem + "_results");
    if (const auto out = root.optional_table("output")) {
        out->allow({"folder", "interval", "vtu_interval", "h5", "node"});
        if (out->has("folder")) c.output.folder = out->path("folder");
        c.output.interval = out->real_or("interval", 0.0, Range::non_negative());
        c.output.vtu_interval = out->real_or("vtu_interval", 0.0, Range::non_negative());
        c.output.h5 = out->boolean_or("h5", true);
        std::set<std::string> names;
        for (const TomlTable& n : out->tables("node")) {
            n.allow({"name", "set"});
            HistoryNode h{n.string("name"), n.string("set")};
            if (h.name.empty() || h.name.find_first_of(" \t\n") != std::string::npos)
                n.fail("name", fmt::format("must be one word (it heads columns of histories.dat), got '{}'", h.name));
            if (!names.insert(h.name).second) n.fail("name", "'" + h.name + "' is used twice");
            c.output.nodes.push_back(h);
        }
    }

    for (const TomlTable& t : root.tables("material")) {
        t.allow({"name", "E", "nu", "rho"});
        const std::string name = t.string("name");
        if (c.materials.count(name)) t.fail("name", "material '" + name + "' is defined twice");
        c.materials.emplace(name, ElasticMaterial::make(name, t.real("E", Range::positive()), t.real("nu", Range::open(-1.0, 0.5)),
                                                        t.real("rho", Range::positive())));
    }
    const auto hand_table = root.optional_table("hand");
    if (hand_table) c.hand = read_hand(*hand_table, c.materials);

    std::set<std::string> names;  // every part, rigid or deformable, has its own name
    auto claim = [&](const TomlTable& t, const std::string& name) {
        if (name.empty()) t.fail("name", "must not be empty");
        if (name == "fingers" || name == "drum" || name.starts_with("finger-"))
            if (c.hand) t.fail("name", "'" + name + "' is a name of the hand's parts");
        if (!names.insert(name).second) t.fail("name", "part name '" + name + "' is used twice");
    };
    for (const TomlTable& t : root.tables("part")) {
        c.parts.push_back(read_part(t, c.materials, c.hand.has_value()));
        claim(t, c.parts.back().name);
    }
    for (const TomlTable& t : root.tables("rigid_part")) {
        c.rigid_parts.push_back(read_rigid_part(t, c.hand.has_value()));
        claim(t, c.rigid_parts.back().name);
    }
    if (c.parts.empty() && !c.hand) root.fail("no [[part]] and no [hand]: the case has nothing deformable");

    // Names a contact or boundary may use.
    std::vector<std::string> deformable, rigid;
    for (const Part& p : c.parts) deformable.push_back(p.name);
    for (const RigidPart& r : c.rigid_parts) rigid.push_back(r.name);
    if (c.hand) {
        deformable.push_back("fingers");
        for (const auto& f : c.hand->hand.fingers) deformable.push_back("finger-" + f.name);
        rigid.push_back("drum");
    }
    std::vector<std::string> all = deformable;
    all.insert(all.end(), rigid.begin(), rigid.end());
    auto has = [](const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); };
    {
        const auto part_tables = root.tables("part");
        for (std::size_t k = 0; k < c.parts.size(); ++k)
            if (!c.parts[k].damping_frame.empty() && !has(rigid, c.parts[k].damping_frame))
                unknown_name(part_tables[k], "damping_frame", c.parts[k].damping_frame, "a rigid part", rigid);
    }
    for (const TomlTable& t : root.tables("contact")) {
        Contact k = read_contact(t);
        if (!has(deformable, k.slave))
            unknown_name(t, "slave", k.slave, has(rigid, k.slave) ? "deformable (a rigid part is a master)" : "a part", deformable);
        if (!has(all, k.master)) unknown_name(t, "master", k.master, "a part or rigid part", all);
        if (t.has("two_way") && has(rigid, k.master))
            t.fail("two_way", "has no effect against a rigid master (its nodes carry no contact forces); remove it");
        c.contacts.push_back(k);
    }
    for (const TomlTable& t : root.tables("rigid_wall")) {
        if (c.hand) t.fail("a case with [hand] takes no [[rigid_wall]]: its symmetry-plane wall is [hand] mirror_contact");
        t.allow({"name", "point", "normal", "slave", "penalty_scale", "depth"});
        RigidWall w;
        w.line = line_of(t);
        w.point = vec3(t, "point");
        w.normal = vec3(t, "normal");
        if (!(w.normal.norm() > 0.0)) t.fail("normal", "must not be zero");
        w.slaves = t.strings("slave");
        if (w.slaves.empty()) t.fail("slave", "names no part");
        for (const std::string& p : w.slaves)
            if (!has(deformable, p))
                unknown_name(t, "slave", p, has(rigid, p) ? "deformable (a rigid part moves by its motion)" : "a part", deformable);
        w.penalty_scale = t.real_or("penalty_scale", 0.1, Range::positive());
        w.depth = t.real_or("depth", w.depth, Range::positive());
        std::string parts;
        for (const std::string& p : w.slaves) parts += (parts.empty() ? "" : "+") + p;
        w.name = t.string_or("name", fmt::format("{} on rigid-wall-{}", parts, c.rigid_walls.size() + 1));
        c.rigid_walls.push_back(w);
    }
    for (const TomlTable& t : root.tables("boundary")) {
        if (c.hand) t.fail("a case with [hand] takes no [[boundary]]: its fingers are tied to the drum and half objects get "
                           "their symmetry plane (ellipsoid half = true)");
        Boundary b = read_boundary(t);
        if (b.kind == Boundary::Kind::follow && !has(rigid, b.rigid_part)) unknown_name(t, "follow", b.rigid_part, "a rigid part", rigid);
        c.boundaries.push_back(b);
    }
    for (const TomlTable& t : root.tables("load")) {
        if (c.hand) t.fail("a case with [hand] takes no [[load]]");
        t.allow({"set", "force", "scale", "scale_curve", "scale_steps"});
        c.loads.push_back({t.string("set"), vec3(t, "force"), curve(t, "scale", Curve()), line_of(t)});
    }
    if (const auto g = root.optional_table("gravity")) {
        g->allow({"g", "scale", "scale_curve", "scale_steps", "on_at"});
        const Vec3 acc = vec3(*g, "g");
        if (g->has("on_at") && (g->has("scale") || g->has("scale_curve") || g->has("scale_steps")))
            g->fail("on_at", "give either on_at or a scale curve");
        Curve k = g->has("on_at") ? Curve::step(g->real("on_at", Range::non_negative())) : curve(*g, "scale", Curve());
        c.gravity = std::pair{acc, k};
    }
    read_phases(root, c);
    c.health_exemptions = check::read_health_exemptions(root);
    doc.finish();
    return c;
}

}  // namespace

ExplicitCase phase_case(const ExplicitCase& c, std::size_t k) {
    if (k >= c.phases.size()) throw InputError(fmt::format("{}: the case has no phase {}", c.source, k));
    ExplicitCase p = c;
    p.phases.clear();
    const double start = c.phases[k].start;
    p.control.end_time = k + 1 < c.phases.size() ? c.phases[k + 1].start : c.control.end_time;
    p.control.name = c.control.name + "-" + c.phases[k].name;
    std::erase_if(p.control.restart_times, [&](double t) { return t <= start || t >= p.control.end_time; });
    for (std::size_t j = 1; j <= k; ++j)
        for (const std::string& name : c.phases[j].release)
            for (Part& part : p.parts)
                if (part.name == name) part.ellipsoid.carried_velocity = Vec3::Zero(), part.ellipsoid.carried_scale = Curve();
    return p;
}

void cut_at(ExplicitCase& c, double t_end) {
    if (!(t_end > 0.0)) throw InputError(fmt::format("{}: an end time must be > 0, got {}", c.source, t_end));
    c.control.end_time = t_end;
    c.cut = true;
    std::erase_if(c.control.restart_times, [&](double t) { return t >= t_end; });
    while (c.phases.size() > 1 && c.phases.back().start >= t_end) c.phases.pop_back();
    if (c.phases.size() == 1) c.phases.clear();
}

ExplicitCase read_case(const std::filesystem::path& path, const std::vector<input::Setting>& settings) {
    input::TomlDocument doc = input::TomlDocument::read(path);
    for (const input::Setting& s : settings) doc.apply(s);
    return from_document(doc);
}

ExplicitCase parse_case(std::string_view text, const std::string& source, const std::filesystem::path& base) {
    return from_document(input::TomlDocument::parse(text, source, base));
}

}  // namespace fem::explicit_case
