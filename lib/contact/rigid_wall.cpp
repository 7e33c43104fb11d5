#include "contact/rigid_wall.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/hdf5.hpp"

namespace fem::contact {

PlanarWall::PlanarWall(std::string name, const Vec3& point, const Vec3& normal, ContactSurface slave, WallOptions o)
    : name_(std::move(name)), point_(point), normal_(normal), slave_(std::move(slave)), opt_(o) {
    if (!(normal.norm() > 0.0) || !normal.allFinite() || !point.allFinite())
        throw InputError(fmt::format("rigid wall '{}': the normal must be a non-zero vector and the point finite", name_));
    normal_.normalize();
    if (slave_.rigid || slave_.nodes.empty())
        throw InputError(fmt::format("rigid wall '{}': the slave surface '{}' must be deformable and have nodes", name_,
                                     slave_.name));
    if (slave_.node_size.size() != slave_.nodes.size() || slave_.node_stiffness.size() != slave_.nodes.size())
        throw InputError(fmt::format("rigid wall '{}': the slave surface '{}' has no node stiffnesses and sizes (build "
                                     "it with ContactSurface::from_part)",
                                     name_, slave_.name));
    if (!(opt_.penalty_scale > 0.0) || !(opt_.depth > 0.0))
        throw InputError(fmt::format("rigid wall '{}': penalty_scale {} and depth {} must be > 0", name_,
                                     opt_.penalty_scale, opt_.depth));
}

double PlanarWall::stability_frequency_squared(std::span<const double> mass) const {
    double w2 = 0.0;
    for (std::size_t i = 0; i < slave_.nodes.size(); ++i) {
        const int n = slave_.nodes[i];
        if (n >= static_cast<int>(mass.size()) || !(mass[n] > 0.0)) continue;
        w2 = std::max(w2, opt_.penalty_scale * slave_.node_stiffness[i] / mass[n]);
    }
    return w2;
}

void PlanarWall::initialize(const NodalState& s) {
    for (int n : slave_.nodes)
        if (n < 0 || n >= s.node_count())
            throw InputError(fmt::format("rigid wall '{}': node {} is out of range (the model has {} nodes)", name_, n,
                                         s.node_count()));
    w2_ = stability_frequency_squared(s.mass);
}

void PlanarWall::add_forces(double, const NodalState& s, std::vector<Vec3>& force, std::vector<Vec3>&) {
    stored_ = 0.0;
    force_on_wall_.setZero();
    active_.clear();
    for (std::size_t i = 0; i < slave_.nodes.size(); ++i) {
        const int node = slave_.nodes[i];
        const double offset = slave_.node_offset.empty() ? 0.0 : slave_.node_offset[i];
        const double g = distance(s.x[node]) - offset;
        if (!(g < 0.0) || -g > opt_.depth) continue;
        const double k = opt_.penalty_scale * slave_.node_stiffness[i];
        const Vec3 f = (-k * g) * normal_;  // Eq 2-30
        force[node] += f;
        force_on_wall_ -= f;
        stored_ += 0.5 * k * g * g;
        max_penetration_ = std::max(max_penetration_, -g);
        max_penetration_fraction_ = std::max(max_penetration_fraction_, -g / slave_.node_size[i]);
        active_.push_back(node);
    }
}

double PlanarWall::stable_time_step(const NodalState&) const {
    return w2_ > 0.0 ? 2.0 / std::sqrt(w2_) : std::numeric_limits<double>::infinity();
}

ContactReport PlanarWall::contact_report() const {
    return {true, max_penetration_, max_penetration_fraction_, stored_, 0.0, force_on_wall_, static_cast<int>(active_.size())};
}

// The forces depend on the positions only; what a restarted run must continue is the statistics.
void PlanarWall::save_state(io::H5Writer& w, const std::string& prefix) const {
    w.write(prefix + "wall", std::vector<double>{stored_, max_penetration_, max_penetration_fraction_,
                                                 force_on_wall_.x(), force_on_wall_.y(), force_on_wall_.z()});
    std::vector<long long> active(active_.begin(), active_.end());
    w.write_ints(prefix + "nodes_in_contact", active);
}

void PlanarWall::restore_state(const io::H5Reader& r, const std::string& prefix) {
    const auto v = r.read(prefix + "wall");
    if (v.size() != 6)
        throw InputError(fmt::format("restart file '{}': rigid wall '{}': bad {}wall", r.path().string(), name_, prefix));
    stored_ = v[0], max_penetration_ = v[1], max_penetration_fraction_ = v[2];
    force_on_wall_ = Vec3(v[3], v[4], v[5]);
    const auto active = r.read_ints(prefix + "nodes_in_contact");
    active_.assign(active.begin(), active.end());
}

PlanarWall& add_rigid_wall(ExplicitModel& model, PlanarWall wall) {
    auto& p = model.add_force_provider(std::make_unique<PlanarWall>(std::move(wall)));
    return static_cast<PlanarWall&>(p);
}

}  // namespace fem::contact
