#include "explicit/relative_damping.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "core/error.hpp"
#include "explicit/solver.hpp"

namespace fem {

RelativeMassDamping::RelativeMassDamping(std::string name, RigidMotion frame, std::vector<std::pair<int, double>> node_alpha)
    : name_(std::move(name)), frame_(std::move(frame)), node_alpha_(std::move(node_alpha)) {
    std::vector<int> nodes;
    for (const auto& [node, alpha] : node_alpha_) {
        if (node < 0) throw InputError(fmt::format("{}: node index {} is negative", name_, node));
        if (!(alpha >= 0.0) || !std::isfinite(alpha))
            throw InputError(fmt::format("{}: alpha = {} of node {} must be finite and >= 0", name_, alpha, node));
        nodes.push_back(node);
    }
    std::sort(nodes.begin(), nodes.end());
    if (const auto twice = std::adjacent_find(nodes.begin(), nodes.end()); twice != nodes.end())
        throw InputError(fmt::format("{}: node {} is listed twice", name_, *twice));
}

void RelativeMassDamping::initialize(const NodalState& s) {
    alpha_mass_.clear();
    rotational_.clear();
    for (const auto& [node, alpha] : node_alpha_) {
        if (node >= s.node_count())
            throw InputError(fmt::format("{}: node {} is not in the model ({} nodes)", name_, node, s.node_count()));
        alpha_mass_.push_back(alpha * s.mass[node]);
        if (!s.rot_index.empty() && s.rot_index[node] >= 0) rotational_.emplace_back(s.rot_index[node], alpha * s.inertia[s.rot_index[node]]);
    }
}

void RelativeMassDamping::add_forces(double t, const NodalState& s, std::vector<Vec3>& force, std::vector<Vec3>& moment) {
    const RigidPose frame = frame_.pose(t);
    for (std::size_t k = 0; k < node_alpha_.size(); ++k) {
        const int i = node_alpha_[k].first;
        force[i] += alpha_mass_[k] * frame.velocity_at(s.x[i]);
    }
    for (const auto& [slot, alpha_inertia] : rotational_) moment[slot] += alpha_inertia * frame.omega;
}

RelativeMassDamping& set_relative_mass_damping(ExplicitModel& model, std::string_view part, double alpha, RigidMotion frame,
                                               std::string_view frame_name) {
    std::vector<std::pair<int, double>> node_alpha;
    for (int node : model.mesh().nodes_of_part(part)) node_alpha.emplace_back(node, alpha);  // throws for an unknown part
    model.set_mass_damping(part, alpha);  // throws for a negative alpha
    return static_cast<RelativeMassDamping&>(model.add_force_provider(std::make_unique<RelativeMassDamping>(
        fmt::format("{} damped relative to {}", part, frame_name), std::move(frame), std::move(node_alpha))));
}

}  // namespace fem
