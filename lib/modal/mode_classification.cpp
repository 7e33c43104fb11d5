// Mode-shape classification by rigid-cross-section fits per slice (see mode_classification.hpp).
#include "modal/mode_classification.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.hpp"

namespace fem::modal {

std::string to_string(ModeType t) {
    switch (t) {
        case ModeType::Bending: return "bending";
        case ModeType::Torsion: return "torsion";
        case ModeType::Elongation: return "elongation";
        case ModeType::Other: return "other";
    }
    return "other";
}

std::string ModeClassification::label() const {
    if (type == ModeType::Bending) return fmt::format("bending (e{})", bending_direction);
    return to_string(type);
}

namespace {

// Running sums of one slice (mass-weighted moments of positions and displacements).
struct Slice {
    std::vector<int> nodes;
};

}  // namespace

ModeClassification classify_mode(std::span<const Vec3> x, std::span<const Vec3> u, std::span<const double> weights,
                                 const ModeClassificationOptions& options) {
    const std::size_t n = x.size();
    if (u.size() != n)
        throw InputError(fmt::format("classify_mode: {} displacements for {} nodes", u.size(), n));
    if (!weights.empty() && weights.size() != n)
        throw InputError(fmt::format("classify_mode: {} weights for {} nodes", weights.size(), n));
    if (n == 0) throw InputError("classify_mode: no nodes");
    if (!(options.axis.norm() > 0.0)) throw InputError("classify_mode: the axis is the zero vector");
    const Vec3 ez = options.axis.normalized();
    Vec3 e1 = options.transverse - options.transverse.dot(ez) * ez;
    if (!(e1.norm() > 1e-12 * options.transverse.norm()) || !(options.transverse.norm() > 0.0))
        throw InputError("classify_mode: the transverse direction is zero or parallel to the axis");
    e1.normalize();
    const Vec3 e2 = ez.cross(e1);
    auto weight = [&](std::size_t i) { return weights.empty() ? 1.0 : weights[i]; };

    double total = 0.0, smin = std::numeric_limits<double>::infinity(), smax = -smin;
    for (std::size_t i = 0; i < n; ++i) {
        const double m = weight(i);
        if (!(m >= 0.0) || !std::isfinite(m))
            throw InputError(fmt::format("classify_mode: weight of node {} is {} (must be >= 0)", i, m));
        if (!u[i].allFinite()) throw InputError(fmt::format("classify_mode: displacement of node {} is not finite", i));
        total += m * u[i].squaredNorm();
        const double s = (x[i] - options.origin).dot(ez);
        smin = std::min(smin, s);
        smax = std::max(smax, s);
    }
    if (!(total > 0.0)) throw InputError("classify_mode: the displacement field is zero (or has zero weight)");

    int slices = options.slices;
    if (slices < 0) throw InputError(fmt::format("classify_mode: slices = {} (>= 0)", slices));
    if (slices == 0) slices = std::clamp(static_cast<int>(n / 40), 4, 60);
    std::vector<Slice> bins(slices);
    const double span = smax - smin;
    for (std::size_t i = 0; i < n; ++i) {
        const double s = (x[i] - options.origin).dot(ez);
        int k = span > 0.0 ? static_cast<int>((s - smin) / span * slices) : 0;
        bins[std::clamp(k, 0, slices - 1)].nodes.push_back(static_cast<int>(i));
    }

    double bend1 = 0.0, bend2 = 0.0, twist = 0.0, stretch = 0.0;
    for (const Slice& slice : bins) {
        double M = 0.0;
        Vec3 centre = Vec3::Zero();
        for (int i : slice.nodes) {
            M += weight(i);
            centre += weight(i) * x[i];
        }
        if (!(M > 0.0)) continue;
        centre /= M;
        // Mass-weighted sums in the slice's frame (xi1, xi2 across, w along the axis).
        double t1 = 0, t2 = 0, w0 = 0, J = 0, torque = 0;
        Eigen::Matrix2d S = Eigen::Matrix2d::Zero();
        Eigen::Vector2d Sw = Eigen::Vector2d::Zero();
        for (int i : slice.nodes) {
            const double m = weight(i);
            const Vec3 d = x[i] - centre;
            const double xi1 = d.dot(e1), xi2 = d.dot(e2);
            const double u1 = u[i].dot(e1), u2 = u[i].dot(e2), w = u[i].dot(ez);
            t1 += m * u1;
            t2 += m * u2;
            w0 += m * w;
            J += m * (xi1 * xi1 + xi2 * xi2);
            torque += m * (xi1 * u2 - xi2 * u1);
            S(0, 0) += m * xi1 * xi1;
            S(0, 1) += m * xi1 * xi2;
            S(1, 1) += m * xi2 * xi2;
            Sw(0) += m * xi1 * w;
            Sw(1) += m * xi2 * w;
        }
        S(1, 0) = S(0, 1);
        t1 /= M;
        t2 /= M;
        w0 /= M;
        // Fitted energies: the fields are mass-orthogonal about the centre, so the projection's norm
        // splits term by term.
        bend1 += M * t1 * t1;
        bend2 += M * t2 * t2;
        stretch += M * w0 * w0;
        if (J > 0.0) twist += torque * torque / J;  // theta = torque / J, energy theta^2 J
        // Axial linear part w = r . xi (section rotations of bending): least squares r = S^+ Sw; its
        // energy r^T S r splits into e1 and e2 parts r_k (S r)_k.
        const Eigen::Vector2d r = S.completeOrthogonalDecomposition().solve(Sw);
        const Eigen::Vector2d Sr = S * r;
        // Bending in the axis-e1 plane (translations along e1) rotates the section about e2, which
        // moves material along the axis in proportion to xi1: the r1 term belongs to e1.
        bend1 += r(0) * Sr(0);
        bend2 += r(1) * Sr(1);
    }

    ModeClassification c;
    c.bending_e1 = bend1 / total;
    c.bending_e2 = bend2 / total;
    c.bending = c.bending_e1 + c.bending_e2;
    c.torsion = twist / total;
    c.elongation = stretch / total;
    c.other = std::max(0.0, 1.0 - c.bending - c.torsion - c.elongation);
    const double best = std::max({c.bending, c.torsion, c.elongation, c.other});
    if (best == c.bending) {
        c.type = ModeType::Bending;
        c.bending_direction = c.bending_e1 >= c.bending_e2 ? 1 : 2;
    } else if (best == c.torsion) {
        c.type = ModeType::Torsion;
    } else if (best == c.elongation) {
        c.type = ModeType::Elongation;
    } else {
        c.type = ModeType::Other;
    }
    return c;
}

ModeClassification classify_mode(std::span<const Vec3> x, std::span<const double> u_flat,
                                 std::span<const double> weights, const ModeClassificationOptions& options) {
    if (u_flat.size() != 3 * x.size())
        throw InputError(fmt::format("classify_mode: {} displacement components for {} nodes (3 per node)",
                                     u_flat.size(), x.size()));
    std::vector<Vec3> u(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) u[i] = Vec3(u_flat[3 * i], u_flat[3 * i + 1], u_flat[3 * i + 2]);
    return classify_mode(x, std::span<const Vec3>(u), weights, options);
}

}  // namespace fem::modal
