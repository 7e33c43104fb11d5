#include "hand/scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <set>

#include <fmt/format.h>

#include "contact/explicit_contact.hpp"
#include "core/error.hpp"
#include "mesh/finger.hpp"

namespace fem::hand {

contact::TimeFunction speed_schedule(const std::vector<SpeedStep>& steps, double ramp) {
    if (steps.empty()) throw InputError("speed schedule: no steps");
    std::vector<std::pair<double, double>> p{{steps.front().from, steps.front().speed}};
    for (std::size_t i = 1; i < steps.size(); ++i) {
        if (!(steps[i].from > steps[i - 1].from + ramp))
            throw InputError(fmt::format("speed schedule: step {} starts at t = {} s, not after step {} (t = {} s)", i,
                                         steps[i].from, i - 1, steps[i - 1].from));
        p.emplace_back(steps[i].from, steps[i - 1].speed);
        p.emplace_back(steps[i].from + ramp, steps[i].speed);
    }
    return contact::TimeFunction(std::move(p), "speed schedule");
}

contact::RigidMotion Plate::motion() const {
    if (schedule.empty()) return contact::RigidMotion::fixed();
    return contact::RigidMotion::translation(direction, speed_schedule(schedule));
}

contact::RigidSurface drum_surface(const Drum& drum, int n, double depth) {
    if (n < 3) throw InputError(fmt::format("drum surface: needs at least 3 segments around (got {})", n));
    contact::RigidSurface r;
    r.surface.name = "drum";
    r.surface.rigid = true;
    for (const auto& l : drum.levels) {
        const int base = static_cast<int>(r.points.size());
        for (int i = 0; i < n; ++i) {
            const double phi = 2.0 * std::numbers::pi * i / n;
            const Vec3 er(std::sin(phi), 0.0, -std::cos(phi));
            r.points.push_back(drum.centre + l.radius * er + l.y_bottom * Vec3::UnitY());
            r.points.push_back(drum.centre + l.radius * er + l.y_top * Vec3::UnitY());
        }
        for (int i = 0; i < n; ++i) {
            const int j = (i + 1) % n;
            contact::Segment s;
            // bottom_i, top_i, top_j, bottom_j: normal y x e_t = e_r (outward).
            s.n = {base + 2 * i, base + 2 * i + 1, base + 2 * j + 1, base + 2 * j};
            s.depth = depth;
            s.area = contact::segment_area(s, r.points);
            r.surface.segments.push_back(s);
        }
    }
    r.motion = drum.motion();
    return r;
}

namespace {

// Co-rotating mass damping (DampingFrame::drum): adds alpha m omega x (x - c) to the finger nodes,
// so that with the solver's -alpha m v the net damping force is -alpha m (v - v_drum(x)). Its work
// is booked by the solver with the force providers' ("contact") energy.
class DrumFrameDamping final : public ForceProvider {
public:
    DrumFrameDamping(contact::RigidMotion drum, std::vector<std::pair<int, double>> node_alpha)
        : drum_(std::move(drum)), node_alpha_(std::move(node_alpha)) {}
    std::string name() const override { return "co-rotating damping frame"; }
    void initialize(const NodalState& s) override {
        mass_.clear();
        for (const auto& [node, a] : node_alpha_) mass_.push_back(a * s.mass[node]);
    }
    void add_forces(double t, const NodalState& s, std::vector<Vec3>& force, std::vector<Vec3>&) override {
        const Vec3 w = drum_.angular_velocity(t), c = drum_.centre() + drum_.translation_at(t);
        for (std::size_t k = 0; k < node_alpha_.size(); ++k) {
            const int i = node_alpha_[k].first;
            force[i] += mass_[k] * w.cross(s.x[i] - c);
        }
    }

private:
    contact::RigidMotion drum_;
    std::vector<std::pair<int, double>> node_alpha_;
    std::vector<double> mass_;
};

// Brackets the contact providers (which the solver calls in order): the first instance notes the
// time, the second adds the elapsed time to the shared total.
class ContactClock final : public ForceProvider {
public:
    ContactClock(std::shared_ptr<double> total, std::shared_ptr<std::chrono::steady_clock::time_point> start, bool stop)
        : total_(std::move(total)), start_(std::move(start)), stop_(stop) {}
    std::string name() const override { return stop_ ? "contact clock (stop)" : "contact clock (start)"; }
    void add_forces(double, const NodalState&, std::vector<Vec3>&, std::vector<Vec3>&) override {
        const auto now = std::chrono::steady_clock::now();
        if (stop_) *total_ += std::chrono::duration<double>(now - *start_).count();
        else *start_ = now;
    }

private:
    std::shared_ptr<double> total_;
    std::shared_ptr<std::chrono::steady_clock::time_point> start_;
    bool stop_;
};

}  // namespace

HandModel::HandModel(const Scene& scene) : scene_(scene) {
    Mesh mesh = hand_mesh(scene_.hand);
    std::map<std::string, ElasticMaterial> material;
    for (const auto& f : scene_.hand.fingers) material["finger-" + f.name] = scene_.hand.rubber;
    std::set<std::string> rigid{"drum"};
    for (const auto& p : scene_.plates) {
        if (!rigid.insert(p.part).second || material.count(p.part))
            throw InputError(fmt::format("hand scene: part name '{}' is used twice", p.part));
    }
    for (auto& o : scene_.objects) {
        if (material.count(o.part) || rigid.count(o.part))
            throw InputError(fmt::format("hand scene: part name '{}' is used twice", o.part));
        Mesh m = hex_ellipsoid(o.semi_axes, o.grid, o.half, o.part);
        m.translate(o.centre);
        if (o.mass > 0.0) {
            const double volume = finger::mesh_quality(m).volume;
            o.material = ElasticMaterial::make(o.material.name, o.material.youngs_modulus, o.material.poissons_ratio,
                                               o.mass / volume);
        }
        std::map<std::string, std::vector<int>> sets;
        for (auto& [name, set] : m.node_sets) sets[name + "-" + o.part] = set;
        m.node_sets = std::move(sets);
        mesh.append(m);
        material[o.part] = o.material;
    }
    model_ = std::make_unique<ExplicitModel>(std::move(mesh));
    const Mesh& msh = model_->mesh();
    for (const auto& [part, mat] : material) {
        model_->add_hex8(part, mat);
        std::set<int> nodes;
        for (int b : msh.blocks_of_part(part))
            for (int c : msh.blocks[b].connectivity) nodes.insert(c);
        part_nodes_[part].assign(nodes.begin(), nodes.end());
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
    drum_motion_ = scene_.hand.drum.motion();
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
        contact::prescribe_rigid_motion(*model_, msh.node_set("root-" + f.name), drum_motion_);
        for (int node : part_nodes_[part]) {
            if (scene_.fingers_start_spinning) model_->set_initial_velocity({node}, drum_motion_.velocity(msh.nodes[node], 0.0));
            node_alpha.emplace_back(node, f.alpha);
        }
    }
    if (scene_.damping_frame == DampingFrame::drum)
        model_->add_force_provider(std::make_unique<DrumFrameDamping>(drum_motion_, std::move(node_alpha)));
    for (const auto& o : scene_.objects) {
        if (o.alpha > 0.0) model_->set_mass_damping(o.part, o.alpha);
        model_->set_initial_velocity(part_nodes_[o.part], o.initial_velocity);
        if (o.half && scene_.symmetry) model_->fix(msh.node_set("symmetry-" + o.part), Dofs::of(Dofs::z));
    }
    if (scene_.gravity.norm() > 0.0) model_->set_gravity(scene_.gravity, scene_.gravity_on);
    // Contact pairs, bracketed by the contact clock.
    clock_ = std::make_shared<double>(0.0);
    auto start = std::make_shared<std::chrono::steady_clock::time_point>();
    model_->add_force_provider(std::make_unique<ContactClock>(clock_, start, false));
    for (const auto& c : scene_.contacts) {
        const std::string name = c.slave + " on " + c.master;
        if (!material.count(c.slave) && c.slave != "fingers")
            throw InputError(fmt::format("hand scene: contact '{}': slave part '{}' is not a deformable part", name, c.slave));
        auto surface = [&](const std::string& part) {
            if (part != "fingers") return contact::ContactSurface::from_part(msh, part, material.at(part));
            std::vector<contact::ContactSurface> each;
            for (const auto& f : scene_.hand.fingers)
                each.push_back(contact::ContactSurface::from_part(msh, "finger-" + f.name, scene_.hand.rubber));
            return contact::ContactSurface::merge("fingers", each);
        };
        auto slave = surface(c.slave);
        contact::ContactOptions opt;
        opt.friction = c.friction;
        opt.penalty_scale = c.penalty_scale;
        Pair p{name, &c, nullptr, slave.mean_segment_size()};
        if (c.master == "drum") {
            auto r = drum_surface(scene_.hand.drum, scene_.drum_segments, 0.02);
            p.contact = &contact::add_contact(*model_, contact::ContactInterface(name, std::move(slave), std::move(r), opt));
        } else if (auto it = std::find_if(scene_.plates.begin(), scene_.plates.end(), [&](const Plate& q) { return q.part == c.master; });
                   it != scene_.plates.end()) {
            auto r = contact::RigidSurface::plane(it->centre, it->u, it->v, it->nu, it->nv, it->depth, it->motion());
            r.surface.name = it->part;
            p.contact = &contact::add_contact(*model_, contact::ContactInterface(name, std::move(slave), std::move(r), opt));
        } else if (material.count(c.master) || c.master == "fingers") {
            auto master = surface(c.master);
            p.element_size = std::min(p.element_size, master.mean_segment_size());
            opt.two_way = c.two_way;
            p.contact = &contact::add_contact(*model_, contact::ContactInterface(name, std::move(slave), std::move(master), opt));
        } else {
            throw InputError(fmt::format("hand scene: contact '{}': master part '{}' is neither a part, a plate nor 'drum'",
                                         name, c.master));
        }
        pairs_.push_back(p);
    }
    model_->add_force_provider(std::make_unique<ContactClock>(clock_, start, true));
}

void HandModel::set_plate_schedule(const std::string& part, std::vector<SpeedStep> schedule) {
    auto it = std::find_if(scene_.plates.begin(), scene_.plates.end(), [&](const Plate& q) { return q.part == part; });
    if (it == scene_.plates.end()) throw InputError(fmt::format("hand model: no plate '{}'", part));
    it->schedule = std::move(schedule);
    for (auto& p : pairs_)
        if (p.spec->master == part) p.contact->rigid()->motion = it->motion();
}

contact::ContactInterface& HandModel::contact(const std::string& name) const {
    for (const auto& p : pairs_)
        if (p.name == name) return *p.contact;
    throw InputError(fmt::format("hand model: no contact pair '{}'", name));
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
