#include "explicit/offset_tie.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/hdf5.hpp"

namespace fem {

OffsetTie::OffsetTie(std::string name, std::vector<int> nodes, std::vector<int> anchors, OffsetTieOptions options)
    : name_(std::move(name)), nodes_(std::move(nodes)), anchors_(std::move(anchors)), options_(options) {
    if (nodes_.size() != anchors_.size() || nodes_.empty())
        throw InputError(fmt::format("tie '{}': {} tied nodes and {} anchors (need one anchor per node, at least one)", name_,
                                     nodes_.size(), anchors_.size()));
    if (engages_late())
        throw InputError(fmt::format("tie '{}': an engage time needs a prescribed motion as the anchor (node anchors hold "
                                     "their reference offsets from the start)", name_));
    for (std::size_t i = 0; i < nodes_.size(); ++i)
        if (nodes_[i] == anchors_[i]) throw InputError(fmt::format("tie '{}': node {} is tied to itself", name_, nodes_[i]));
    check_options();
}

OffsetTie::OffsetTie(std::string name, std::vector<int> nodes, RigidMotion motion, OffsetTieOptions options)
    : name_(std::move(name)), nodes_(std::move(nodes)), motion_(std::move(motion)), options_(options) {
    if (nodes_.empty()) throw InputError(fmt::format("tie '{}': no tied nodes", name_));
    std::vector<int> sorted = nodes_;
    std::sort(sorted.begin(), sorted.end());
    if (const auto it = std::adjacent_find(sorted.begin(), sorted.end()); it != sorted.end())
        throw InputError(fmt::format("tie '{}': node {} is listed twice", name_, *it));
    check_options();
}

void OffsetTie::check_options() const {
    if (!(options_.frequency > 0.0) || !(options_.damping_ratio >= 0.0))
        throw InputError(fmt::format("tie '{}': frequency must be positive and the damping ratio non-negative", name_));
    if (std::isnan(options_.release_time)) throw InputError(fmt::format("tie '{}': the release time is not a number", name_));
    if (std::isnan(options_.engage_time) || !(options_.engage_time < options_.release_time))
        throw InputError(fmt::format("tie '{}': the engage time ({} s) must come before the release time ({} s)", name_,
                                     options_.engage_time, options_.release_time));
}

void OffsetTie::initialize(const NodalState& s) {
    const int n = static_cast<int>(nodes_.size());
    offset_.resize(n);
    k_.resize(n);
    c_.resize(n);
    const double w = 2.0 * std::numbers::pi * options_.frequency;
    if (motion_) {
        // Tied to a prescribed motion: the anchor point cannot move back, so each tie is a spring
        // and dashpot on the tied node alone (omega^2 = k / m_p, the damped bound as below).
        dt_ = std::numeric_limits<double>::infinity();
        for (int i = 0; i < n; ++i) {
            const int p = nodes_[i];
            if (p < 0 || p >= s.node_count()) throw InputError(fmt::format("tie '{}': node {} is not in the mesh", name_, p));
            if (!(s.mass[p] > 0.0)) throw InputError(fmt::format("tie '{}': tied node {} has no mass", name_, p));
            offset_[i] = s.X[p];
            k_[i] = s.mass[p] * w * w;
            c_[i] = 2.0 * options_.damping_ratio * s.mass[p] * w;
            const double zeta = c_[i] / s.mass[p] / (2.0 * w);
            dt_ = std::min(dt_, 2.0 / w * (std::sqrt(1.0 + zeta * zeta) - zeta));
        }
        return;
    }
    std::map<int, std::pair<double, double>> at_anchor;  // anchor: (sum k, sum k |r|^2)
    for (int i = 0; i < n; ++i) {
        const int p = nodes_[i], a = anchors_[i];
        if (p < 0 || a < 0 || p >= s.node_count() || a >= s.node_count())
            throw InputError(fmt::format("tie '{}': node {} or anchor {} is not in the mesh", name_, p, a));
        offset_[i] = s.X[p] - s.X[a];
        if (offset_[i].norm() > 0.0 && s.rot_index[a] < 0)
            throw InputError(fmt::format("tie '{}': anchor node {} carries no rotations (it must belong to a shell or beam part)", name_, a));
        if (!(s.mass[p] > 0.0)) throw InputError(fmt::format("tie '{}': tied node {} has no mass", name_, p));
        k_[i] = s.mass[p] * w * w;
        c_[i] = 2.0 * options_.damping_ratio * s.mass[p] * w;
        auto& [ks, kr] = at_anchor[a];
        ks += k_[i];
        kr += k_[i] * offset_[i].squaredNorm();
    }
    // The stable step of each tie, its anchor's share included: omega^2 <= k / m_p + sum k / m_a +
    // sum k r^2 / I_a, and with a dashpot the damped central-difference bound 2 / omega (sqrt(1 +
    // zeta^2) - zeta), zeta = c (1 / m_p + 1 / m_a + r^2 / I_a) / (2 omega). The dashpot's zeta is
    // set on the tied node's mass; on a shell node's small (scaled) rotational inertia the same
    // dashpot is heavily overdamped, and without this bound it was unstable (unit test).
    dt_ = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) {
        const int p = nodes_[i], a = anchors_[i], ra = s.rot_index[a];
        const auto& [ks, kr] = at_anchor[a];
        double w2 = k_[i] / s.mass[p] + ks / s.mass[a];
        double flex = 1.0 / s.mass[p] + 1.0 / s.mass[a];
        if (ra >= 0) w2 += kr / s.inertia[ra], flex += offset_[i].squaredNorm() / s.inertia[ra];
        const double wi = std::sqrt(w2), zeta = c_[i] * flex / (2.0 * wi);
        dt_ = std::min(dt_, 2.0 / wi * (std::sqrt(1.0 + zeta * zeta) - zeta));
    }
}

void OffsetTie::add_forces(double t, const NodalState& s, std::vector<Vec3>& force, std::vector<Vec3>& moment) {
    max_gap_ = 0.0;
    total_force_.setZero();
    if (!holding(t)) return;
    if (motion_) {
        const RigidPose pose = motion_->pose(t);
        if (engages_late() && !engaged_) {
            // Engaging now: hold each node at the motion's material point where it is (X = R^T (x - d)).
            for (std::size_t i = 0; i < nodes_.size(); ++i) offset_[i] = pose.R.transpose() * (s.x[nodes_[i]] - pose.d);
            engaged_ = true;
        }
        for (std::size_t i = 0; i < nodes_.size(); ++i) {
            const int p = nodes_[i];
            const Vec3 gap = s.x[p] - pose.position(offset_[i]);
            const Vec3 f = -k_[i] * gap - c_[i] * (s.v[p] - pose.velocity(offset_[i]));
            force[p] += f;
            max_gap_ = std::max(max_gap_, gap.norm());
            total_force_ += f;
        }
        return;
    }
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        const int p = nodes_[i], a = anchors_[i], ra = s.rot_index[a];
        const Vec3 r = ra >= 0 ? Vec3(s.rotation[ra] * offset_[i]) : offset_[i];
        const Vec3 w = ra >= 0 ? s.omega[ra] : Vec3::Zero();
        const Vec3 gap = s.x[p] - s.x[a] - r;
        const Vec3 f = -k_[i] * gap - c_[i] * (s.v[p] - s.v[a] - w.cross(r));
        force[p] += f;
        force[a] -= f;
        if (ra >= 0) moment[ra] += r.cross(-f);
        max_gap_ = std::max(max_gap_, gap.norm());
        total_force_ += f;
    }
}

// Only a late engagement has state: whether it happened and the held points it captured.
void OffsetTie::save_state(io::H5Writer& w, const std::string& prefix) const {
    if (!engages_late()) return;
    std::vector<double> held{engaged_ ? 1.0 : 0.0};
    for (const Vec3& X : offset_) held.insert(held.end(), {X.x(), X.y(), X.z()});
    w.write(prefix + "engaged_and_held_points", held);
}

void OffsetTie::restore_state(const io::H5Reader& r, const std::string& prefix) {
    if (!engages_late()) return;
    const auto held = r.read(prefix + "engaged_and_held_points");
    if (held.size() != 1 + 3 * offset_.size())
        throw InputError(fmt::format("restart file '{}': tie '{}': {} values in {}engaged_and_held_points, expected {}", r.path().string(),
                                     name_, held.size(), prefix, 1 + 3 * offset_.size()));
    engaged_ = held[0] != 0.0;
    for (std::size_t i = 0; i < offset_.size(); ++i) offset_[i] = Vec3(held[1 + 3 * i], held[2 + 3 * i], held[3 + 3 * i]);
}

double OffsetTie::stable_time_step(const NodalState&) const { return dt_ > 0.0 ? dt_ : std::numeric_limits<double>::infinity(); }

}  // namespace fem
