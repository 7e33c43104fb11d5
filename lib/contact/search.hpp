#pragma once
// Contact search (thesis Sec 2.3.6: "each slave node is checked for penetration through the master
// surface"): which master segments can a slave node touch? Never all pairs: a uniform spatial hash
// grid of the segments' bounding boxes, and a Verlet candidate list kept between rebuilds.
//
// Capture region of a segment: a node can only be in contact with it when it lies behind the face
// (gap in [-depth, 0)) and projects onto it within `lateral` (the edge tolerance): the prism swept
// by the face moved back along its normal by `depth`, widened by `lateral`. Its box is the box of
// the corner nodes x_k and of x_k - depth n_k (n_k the unit normal at corner k), widened by
// lateral + depth max|n_j - n_k| (the spread of the normal over a warped face) + margin. Boxes
// are anisotropic: a flat face's box is thin in-plane-wide, not a cube of the depth. A two-sided
// segment (a shell with thickness, Segment::two_sided) captures on both sides: x_k + depth n_k too.
//
// Rebuild rule (why nothing is missed): every slave node's candidates are the segments whose
// widened box contains it at the rebuild. Let d_s and d_m be the largest displacements of any
// slave node and any master node since the rebuild. A point of the capture prism x(xi) - t n(xi)
// moves by at most d_m (the face point) plus t |dn| with |dn| <~ 2 d_m / h (the normal of a face of
// size h whose corners move by d_m turns by at most about 2 d_m / h), so at most d_m (1 + 2 depth
// / h). A node in the capture region now was within d_s + d_m (1 + 2 depth / h) of the region at
// the rebuild. The list therefore stays complete while d_s + f d_m <= margin, f = max over the
// segments of 1 + 2 depth / h, and it is rebuilt on the first cycle where that fails (and at
// the latest every max_interval cycles). Cost per cycle: O(surface nodes) to track d_s, d_m; per
// rebuild: O(segments x cells per box + nodes x candidates), i.e. proportional to the surface.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace fem::io {
class H5Writer;
class H5Reader;
}  // namespace fem::io

namespace fem::contact {

struct Box {
    Vec3 lo, hi;
    bool contains(const Vec3& p) const {
        return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
    }
};

/// A uniform grid hashed into buckets: each segment box is entered in every cell it overlaps;
/// a point query returns the boxes entered in the point's cell that contain the point.
class SpatialHashGrid {
public:
    /// cell <= 0: chosen as the mean box extent (so a box overlaps a few cells).
    void build(std::span<const Box> boxes, double cell = 0.0);
    /// Appends to `out` the indices of the boxes that contain p (each once, ascending).
    void query(const Vec3& p, std::vector<int>& out) const;
    double cell_size() const { return h_; }

private:
    std::uint64_t bucket(long ix, long iy, long iz) const;
    std::span<const Box> boxes_;
    double h_ = 1.0;
    Vec3 origin_ = Vec3::Zero();
    std::vector<int> offset_, items_;  // CSR: bucket -> box indices
};

/// Brute force: every box that contains p (for tests).
void brute_force_query(std::span<const Box> boxes, const Vec3& p, std::vector<int>& out);

/// Verlet candidate lists of slave nodes against master segments with the rebuild rule above.
class CandidateList {
public:
    /// margin > 0 [m]; max_interval >= 1 cycles.
    CandidateList(double margin, int max_interval);
    /// Updates the list for the current positions: rebuilds when needed (returns true then).
    /// slave_x: position of every slave node; master_x: position of every master node (indexed
    /// by the segments' node numbers); segments: node lists (count 3 or 4); depth[i], lateral[i]:
    /// capture region of segment i (see above; the margin is added here); master_nodes: every
    /// node the segments use; turn_factor: f of the rebuild rule. exclude(slave, segment)
    /// removes self pairs.
    template <class SegmentRange, class Exclude>
    bool update(std::span<const Vec3> slave_x, std::span<const Vec3> master_x, const SegmentRange& segments,
                std::span<const double> depth, std::span<const double> lateral, const std::vector<int>& master_nodes,
                double turn_factor, Exclude exclude);
    /// The widened box of the last rebuild of segment s.
    const Box& box(int s) const { return boxes_[s]; }
    std::span<const int> candidates(int slave) const {
        return {items_.data() + offset_[slave], static_cast<std::size_t>(offset_[slave + 1] - offset_[slave])};
    }
    long rebuilds() const { return rebuilds_; }
    long cycles() const { return cycles_; }
    double margin() const { return margin_; }
    void force_rebuild() { since_ = -1; }
    /// Restart: the lists, the positions of the last rebuild and the counters, under `prefix`.
    void save_state(io::H5Writer& w, const std::string& prefix) const;
    void restore_state(const io::H5Reader& r, const std::string& prefix);

private:
    double margin_;
    int max_interval_;
    int since_ = -1;  // cycles since the last rebuild (-1: never built)
    long rebuilds_ = 0, cycles_ = 0;
    std::vector<Vec3> slave0_, master0_;  // positions at the last rebuild
    std::vector<int> offset_, items_;
    std::vector<Box> boxes_;
    SpatialHashGrid grid_;
    std::vector<int> scratch_;
};

// ---------------------------------------------------------------------------------------------
template <class SegmentRange, class Exclude>
bool CandidateList::update(std::span<const Vec3> slave_x, std::span<const Vec3> master_x, const SegmentRange& segments,
                           std::span<const double> depth, std::span<const double> lateral,
                           const std::vector<int>& master_nodes, double turn_factor, Exclude exclude) {
    ++cycles_;
    bool rebuild = since_ < 0 || since_ + 1 >= max_interval_ || slave0_.size() != slave_x.size();
    if (!rebuild) {
        double ds = 0.0, dm = 0.0;
        for (std::size_t i = 0; i < slave_x.size(); ++i) ds = std::max(ds, (slave_x[i] - slave0_[i]).squaredNorm());
        for (std::size_t i = 0; i < master_nodes.size(); ++i)
            dm = std::max(dm, (master_x[master_nodes[i]] - master0_[i]).squaredNorm());
        rebuild = std::sqrt(ds) + turn_factor * std::sqrt(dm) > margin_;
    }
    if (!rebuild) {
        ++since_;
        return false;
    }
    since_ = 0;
    ++rebuilds_;
    slave0_.assign(slave_x.begin(), slave_x.end());
    master0_.resize(master_nodes.size());
    for (std::size_t i = 0; i < master_nodes.size(); ++i) master0_[i] = master_x[master_nodes[i]];
    const int ns = static_cast<int>(segments.size());
    boxes_.resize(ns);
    for (int s = 0; s < ns; ++s) {
        const auto& seg = segments[s];
        // Unit normal at each corner (cross product of the two edges meeting there).
        Vec3 n[4];
        for (int k = 0; k < seg.count; ++k) {
            const Vec3& a = master_x[seg.n[k]];
            const Vec3 e1 = master_x[seg.n[(k + 1) % seg.count]] - a, e0 = master_x[seg.n[(k + seg.count - 1) % seg.count]] - a;
            const Vec3 c = e1.cross(e0);
            const double l = c.norm();
            n[k] = l > 0 ? Vec3(c / l) : Vec3::Zero();
        }
        double spread = 0.0;
        for (int j = 0; j < seg.count; ++j)
            for (int k = j + 1; k < seg.count; ++k) spread = std::max(spread, (n[j] - n[k]).norm());
        Box b{master_x[seg.n[0]], master_x[seg.n[0]]};
        for (int k = 0; k < seg.count; ++k) {
            const Vec3& a = master_x[seg.n[k]];
            const Vec3 back = a - depth[s] * n[k];
            const Vec3 front = seg.two_sided ? Vec3(a + depth[s] * n[k]) : a;
            b.lo = b.lo.cwiseMin(front).cwiseMin(back);
            b.hi = b.hi.cwiseMax(front).cwiseMax(back);
        }
        const double r = lateral[s] + depth[s] * spread + margin_;
        b.lo.array() -= r;
        b.hi.array() += r;
        boxes_[s] = b;
    }
    grid_.build(boxes_);
    offset_.assign(slave_x.size() + 1, 0);
    items_.clear();
    for (std::size_t i = 0; i < slave_x.size(); ++i) {
        scratch_.clear();
        grid_.query(slave_x[i], scratch_);
        for (int s : scratch_)
            if (!exclude(static_cast<int>(i), s)) items_.push_back(s);
        offset_[i + 1] = static_cast<int>(items_.size());
    }
    return true;
}

}  // namespace fem::contact
