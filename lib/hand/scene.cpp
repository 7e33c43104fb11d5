#include "hand/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include <fmt/format.h>

#include "contact/explicit_contact.hpp"
#include "contact/rigid_wall.hpp"
#include "core/error.hpp"
#include "explicit/relative_damping.hpp"
#include "explicit/tet_groups.hpp"
#include "mesh/finger.hpp"
#include "mesh/mesh.hpp"

namespace fem::hand {

Scene seen_from(Scene s, double t0) {
    if (t0 == 0.0) return s;
    if (!(t0 > 0.0)) throw InputError(fmt::format("hand scene: a start time must be >= 0, got {}", t0));
    for (const auto& o : s.meshes)
        if (!o.ties.empty())
            throw InputError(fmt::format("hand scene: mesh object '{}' is tied to a plate and cannot be seen from a later time "
                                         "(not written)", o.part));
    for (const auto& p : s.plates)
        if (p.path) throw InputError(fmt::format("hand scene: plate '{}' moves on a path and cannot be seen from a later time (not written)", p.part));
    if (s.turn.omega.integral(t0) != 0.0)
        throw InputError(fmt::format("hand scene: the hand has turned before the start time {} s", t0));
    Drum& d = s.hand.drum;
    d.initial_angle += d.omega.integral(t0);
    d.omega = d.omega.shifted(t0);
    s.turn.omega = s.turn.omega.shifted(t0);
    for (auto& o : s.objects) {
        if (o.carried_velocity != Vec3::Zero() && o.carried_scale.integral(t0) != t0)
            throw InputError(fmt::format("hand scene: the carriage of '{}' changes before the start time {} s", o.part, t0));
        o.centre += o.initial_velocity * t0;
        o.carried_scale = o.carried_scale.shifted(t0);
    }
    for (auto& o : s.meshes) o.mesh.translate(o.initial_velocity * t0);
    for (auto& p : s.plates) {
        p.centre += p.direction * p.speed.integral(t0);
        p.speed = p.speed.shifted(t0);
    }
    s.gravity_curve = s.gravity_curve.shifted(t0);
    return s;
}

namespace {
// Scene::mirror_contact: the plane z = the half object's centre z, where a finger meets its mirror image.
// The plane z = const of a half mesh object's cut (MeshObject::symmetry_set); InputError when its
// nodes do not lie on one such plane (1e-9 of the object's size).
double cut_plane_z(const MeshObject& o) {
    const auto& set = o.mesh.node_set(o.symmetry_set);
    if (set.empty())
        throw InputError(fmt::format("hand scene: the symmetry set '{}' of '{}' has no nodes", o.symmetry_set, o.part));
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, size = 0.0;
    for (int n : set) lo = std::min(lo, o.mesh.nodes[n].z()), hi = std::max(hi, o.mesh.nodes[n].z());
    for (const Vec3& x : o.mesh.nodes) size = std::max(size, (x - o.mesh.nodes[set.front()]).norm());
    if (hi - lo > 1e-9 * size)
        throw InputError(fmt::format("hand scene: the symmetry set '{}' of '{}' does not lie on a plane z = const (z from {} to {})",
                                     o.symmetry_set, o.part, lo, hi));
    return 0.5 * (lo + hi);
}

double mirror_plane_z(const Scene& s) {
    const auto half = std::find_if(s.objects.begin(), s.objects.end(), [](const EllipsoidObject& o) { return o.half; });
    if (half != s.objects.end() && s.symmetry) return half->centre.z();
    const auto cut = std::find_if(s.meshes.begin(), s.meshes.end(), [](const MeshObject& o) { return !o.symmetry_set.empty(); });
    if (cut == s.meshes.end() || !s.symmetry)
        throw InputError("hand scene: mirror_contact needs a half object and its symmetry plane (symmetry = true)");
    return cut_plane_z(*cut);
}
}  // namespace

HandModel::HandModel(const Scene& scene) : scene_(scene) {
    const double mirror_z = scene_.mirror_contact ? mirror_plane_z(scene_) : 0.0;
    Mesh mesh = hand_mesh(scene_.hand);
    std::map<std::string, ElasticMaterial> material;
    for (const auto& f : scene_.hand.fingers) material["finger-" + f.name] = scene_.hand.rubber;
    std::set<std::string> rigid{"drum"};
    for (const auto& p : scene_.plates) {
        if (!rigid.insert(p.part).second || material.count(p.part))
            throw InputError(fmt::format("hand scene: part name '{}' is used twice", p.part));
    }
    // A deformable object's mesh into the model's mesh: its part name must be new, its node sets are
    // renamed "<set>-<part>" (ellipsoid and mesh objects alike).
    auto add_object = [&](Mesh m, const std::string& part, const ElasticMaterial& mat) {
        std::map<std::string, std::vector<int>> sets;
        for (auto& [name, set] : m.node_sets) sets[name + "-" + part] = set;
        m.node_sets = std::move(sets);
        mesh.append(m);
        material[part] = mat;
    };
    auto check_new_part = [&](const std::string& part) {
        if (material.count(part) || rigid.count(part))
            throw InputError(fmt::format("hand scene: part name '{}' is used twice", part));
    };
    for (auto& o : scene_.objects) {
        check_new_part(o.part);
        Mesh m = hex_ellipsoid(o.semi_axes, o.grid, o.half, o.part);
        m.translate(o.centre);
        if (o.mass > 0.0) {
            const double volume = finger::mesh_quality(m).volume;
            o.material = ElasticMaterial::make(o.material.name, o.material.youngs_modulus, o.material.poissons_ratio,
                                               o.mass / volume);
        }
        add_object(std::move(m), o.part, o.material);
    }
    std::set<std::string> tet_parts;
    std::map<std::string, double> hourglass_qm;  // hexahedral mesh objects' own QM (default Hex8Options)
    std::map<std::string, BulkViscosity> bulk;   // mesh objects' own bulk viscosity (default Table 2-1's)
    for (const auto& o : scene_.meshes) {
        check_new_part(o.part);
        const Mesh& m = o.mesh;
        bool tets = false, hexes = false;
        for (const auto& b : m.blocks) {
            if (b.part != o.part)
                throw InputError(fmt::format("hand scene: mesh object '{}' has a block of part '{}' (one part per mesh object)", o.part, b.part));
            tets |= b.shape == ElementShape::Tet4 || b.shape == ElementShape::Tet10;
            hexes |= b.shape == ElementShape::Hex8;
            if (b.shape != ElementShape::Tet4 && b.shape != ElementShape::Tet10 && b.shape != ElementShape::Hex8)
                throw InputError(fmt::format("hand scene: mesh object '{}' has {} elements (tet4, tet10 or hex8 only)", o.part, to_string(b.shape)));
        }
        if (tets && hexes) throw InputError(fmt::format("hand scene: mesh object '{}' mixes tetrahedra and hexahedra", o.part));
        if (m.blocks.empty()) throw InputError(fmt::format("hand scene: mesh object '{}' has no elements", o.part));
        if (tets) tet_parts.insert(o.part);
        else hourglass_qm[o.part] = o.hourglass_qm;
        bulk[o.part] = o.bulk;
        if (!o.symmetry_set.empty()) cut_plane_z(o);  // refuses a cut that is not a plane z = const
        add_object(m, o.part, o.material);
    }
    for (const auto& p : scene_.plates) mesh.append(parallelogram_quad4(p.centre, p.u, p.v, p.nu, p.nv, p.part));
    mesh.append(drum_mesh(scene_.hand.drum, scene_.drum_segments));
    model_ = std::make_unique<ExplicitModel>(std::move(mesh));
    const Mesh& msh = model_->mesh();
    for (const auto& [part, mat] : material) {
        const BulkViscosity q = bulk.count(part) ? bulk.at(part) : BulkViscosity{};
        const bool bulk_on = q.quadratic > 0.0 || q.linear > 0.0;
        if (tet_parts.count(part)) {
            add_tets(*model_, part, mat, {.bulk_viscosity = bulk_on, .bulk = q});
        } else {
            Hex8Options o{.bulk_viscosity = bulk_on, .bulk = q};
            if (const auto qm = hourglass_qm.find(part); qm != hourglass_qm.end()) o.hourglass_qm = qm->second;
            model_->add_hex8(part, mat, o);
        }
        part_nodes_[part] = msh.nodes_of_part(part);
        // Lumped masses (volume / 8 per node) for centres of mass.
        std::map<int, double> lm;
        double total = 0.0;
        for (int b : msh.blocks_of_part(part))
            for (int e = 0; e < msh.blocks[b].size(); ++e) {
                const auto el = msh.blocks[b].element(e);
                const double m = mat.density * contact::element_volume(msh.blocks[b].shape, msh.element_coordinates(b, e));
                for (int node : el) lm[node] += m / el.size();
                total += m;
            }
        for (int node : part_nodes_[part]) lumped_[part].push_back(lm[node]);
        part_mass_[part] = total;
    }
    drum_motion_ = compose(RigidMotion::rotation(scene_.turn.point, scene_.turn.axis, scene_.turn.omega),
                           scene_.hand.drum.motion());
    model_->add_rigid_part("drum", drum_motion_);
    for (const auto& p : scene_.plates) model_->add_rigid_part(p.part, p.motion());
    block_finger_.assign(msh.blocks.size(), "");
    node_finger_.assign(msh.node_count(), "");
    for (const auto& f : scene_.hand.fingers) {
        for (int b : msh.blocks_of_part("finger-" + f.name)) block_finger_[b] = f.name;
        for (int n : part_nodes_["finger-" + f.name]) node_finger_[n] = f.name;
    }
    // Fingers: damping, roots tied to the drum, initial velocity.
    std::vector<std::pair<int, double>> node_alpha;
    for (const auto& f : scene_.hand.fingers) {
        const std::string part = "finger-" + f.name;
        model_->set_mass_damping(part, f.alpha);
        model_->prescribe_motion(msh.node_set("root-" + f.name), drum_motion_);
        for (int node : part_nodes_[part]) {
            if (scene_.fingers_start_spinning) model_->set_initial_velocity({node}, drum_motion_.velocity(msh.nodes[node], 0.0));
            node_alpha.emplace_back(node, f.alpha);
        }
    }
    if (scene_.damping_frame == DampingFrame::drum)
        // Co-rotating mass damping: -alpha m (v - v_drum(x)) on the finger nodes (relative_damping.hpp).
        model_->add_force_provider(std::make_unique<RelativeMassDamping>("co-rotating damping frame", drum_motion_, std::move(node_alpha)));
    for (const auto& o : scene_.objects) {
        if (o.alpha > 0.0) model_->set_mass_damping(o.part, o.alpha);
        model_->set_initial_velocity(part_nodes_[o.part], o.initial_velocity);
        for (int d = 0; d < 3; ++d)
            if (o.carried_velocity[d] != 0.0)
                model_->prescribe_velocity(part_nodes_[o.part], d, o.carried_velocity[d], o.carried_scale);
        if (o.half && scene_.symmetry) model_->add_symmetry_plane(Vec3::UnitZ(), msh.node_set("symmetry-" + o.part));
    }
    for (const auto& o : scene_.meshes) {
        if (o.alpha > 0.0) model_->set_mass_damping(o.part, o.alpha);
        model_->set_initial_velocity(part_nodes_[o.part], o.initial_velocity);
        if (!o.symmetry_set.empty() && scene_.symmetry)
            model_->add_symmetry_plane(Vec3::UnitZ(), msh.node_set(o.symmetry_set + "-" + o.part));
        for (const auto& t : o.ties) {
            const auto plate = std::find_if(scene_.plates.begin(), scene_.plates.end(), [&](const Plate& q) { return q.part == t.plate; });
            if (plate == scene_.plates.end())
                throw InputError(fmt::format("hand scene: '{}' is tied to plate '{}', which is not in the scene", o.part, t.plate));
            auto& tie = model_->add_force_provider(std::make_unique<OffsetTie>(
                fmt::format("{} {} on {}", o.part, t.node_set, t.plate), msh.node_set(t.node_set + "-" + o.part), plate->motion(), t.options));
            ties_[{o.part, t.plate}] = static_cast<const OffsetTie*>(&tie);
        }
    }
    if (scene_.gravity.norm() > 0.0) model_->set_gravity(scene_.gravity, scene_.gravity_curve);
    // Contact pairs.
    auto object_surface = [&](const std::string& part) {
        auto s = contact::ContactSurface::from_part(msh, part, material.at(part));
        for (const auto& o : scene_.objects)
            if (o.part == part && o.half && scene_.symmetry) s.remove_faces_on(msh.node_set("symmetry-" + o.part));
        for (const auto& o : scene_.meshes)
            if (o.part == part && !o.symmetry_set.empty() && scene_.symmetry) s.remove_faces_on(msh.node_set(o.symmetry_set + "-" + o.part));
        return s;
    };
    auto fingers_surface = [&] {  // every finger as one surface (one search, one stable-step bound)
        std::vector<contact::ContactSurface> each;
        for (const auto& f : scene_.hand.fingers)
            each.push_back(contact::ContactSurface::from_part(msh, "finger-" + f.name, scene_.hand.rubber));
        return contact::ContactSurface::merge("fingers", each);
    };
    for (const auto& c : scene_.contacts) {
        const std::string name = c.slave + " on " + c.master;
        if (!material.count(c.slave) && c.slave != "fingers")
            throw InputError(fmt::format("hand scene: contact '{}': slave part '{}' is not a deformable part", name, c.slave));
        auto surface = [&](const std::string& part) {
            return part == "fingers" ? fingers_surface() : object_surface(part);
        };
        auto slave = surface(c.slave);
        contact::ContactOptions opt;
        opt.friction = c.friction;
        opt.penalty_scale = c.penalty_scale;
        Pair p{name, &c, nullptr};
        if (c.master == "drum") {
            auto r = contact::ContactSurface::rigid_part(msh, "drum", 0.02);
            p.contact = &contact::add_contact(*model_, contact::ContactInterface(name, std::move(slave), std::move(r), opt));
        } else if (auto it = std::find_if(scene_.plates.begin(), scene_.plates.end(), [&](const Plate& q) { return q.part == c.master; });
                   it != scene_.plates.end()) {
            auto r = contact::ContactSurface::rigid_part(msh, it->part, it->depth);
            opt.track_approach_side = it->track_approach_side;
            p.contact = &contact::add_contact(*model_, contact::ContactInterface(name, std::move(slave), std::move(r), opt));
        } else if (material.count(c.master) || c.master == "fingers") {
            auto master = surface(c.master);
            opt.two_way = c.two_way;
            p.contact = &contact::add_contact(*model_, contact::ContactInterface(name, std::move(slave), std::move(master), opt));
        } else {
            throw InputError(fmt::format("hand scene: contact '{}': master part '{}' is neither a part, a plate nor 'drum'",
                                         name, c.master));
        }
        pairs_.push_back(p);
    }
    // The fingers against their mirror images: a fixed frictionless planar wall on the symmetry plane
    // (contact/rigid_wall.hpp), its normal -z towards the fingers' side, the pairs' default penalty
    // scale. (Until 2026-12-02 a fixed rigid plate of 20 mm quad segments through the segment contact:
    // the same springs in the same plane, at ~25 % of a football case's CPU for the search.)
    if (scene_.mirror_contact) {
        contact::WallOptions wo;
        wo.penalty_scale = ContactPair{}.penalty_scale;
        wo.depth = kMirrorDepth;
        const Vec3& c = scene_.hand.drum.centre;
        mirror_wall_ = &contact::add_rigid_wall(
            *model_, contact::PlanarWall("fingers on mirror-plane", Vec3(c.x(), c.y(), mirror_z), -Vec3::UnitZ(),
                                         fingers_surface(), wo));
    }
}

contact::ContactInterface& HandModel::contact(const std::string& name) const {
    for (const auto& p : pairs_)
        if (p.name == name) return *p.contact;
    throw InputError(fmt::format("hand model: no contact pair '{}'", name));
}

std::vector<std::pair<std::string, ContactReport>> HandModel::contact_reports() const {
    std::vector<std::pair<std::string, ContactReport>> r;
    for (const auto& p : pairs_) r.emplace_back(p.name, contact::contact_report(*p.contact));
    if (mirror_wall_) r.emplace_back(mirror_wall_->name(), mirror_wall_->contact_report());
    return r;
}

const OffsetTie& HandModel::tie(const std::string& part, const std::string& plate) const {
    const auto it = ties_.find({part, plate});
    if (it == ties_.end()) throw InputError(fmt::format("hand model: '{}' is not tied to plate '{}'", part, plate));
    return *it->second;
}

std::vector<int> HandModel::part_nodes(const std::string& part) const {
    auto it = part_nodes_.find(part);
    if (it == part_nodes_.end()) throw InputError(fmt::format("hand model: no deformable part '{}'", part));
    return it->second;
}

double HandModel::part_mass(const std::string& part) const {
    auto it = part_mass_.find(part);
    if (it == part_mass_.end()) throw InputError(fmt::format("hand model: no deformable part '{}'", part));
    return it->second;
}

Vec3 HandModel::centre_of_mass(const std::string& part, std::span<const Vec3> x) const {
    const auto& nodes = part_nodes_.at(part);
    const auto& m = lumped_.at(part);
    Vec3 s = Vec3::Zero();
    double total = 0.0;
    for (std::size_t k = 0; k < nodes.size(); ++k) s += m[k] * x[nodes[k]], total += m[k];
    return s / total;
}

const std::string& HandModel::finger_of_block(int block) const { return block_finger_.at(block); }

const std::string& HandModel::finger_of_node(int node) const { return node_finger_.at(node); }

int HandModel::tip_node(const std::string& finger) const { return mesh().node_set("tip-centre-" + finger)[0]; }

Vec3 HandModel::plate_centre(const std::string& part, double t) const {
    for (const auto& p : scene_.plates)
        if (p.part == part) return p.motion().position(p.centre, t);
    throw InputError(fmt::format("hand model: no plate '{}'", part));
}

}  // namespace fem::hand
