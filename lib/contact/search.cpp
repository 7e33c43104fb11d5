#include "contact/search.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace fem::contact {

std::uint64_t SpatialHashGrid::bucket(long ix, long iy, long iz) const {
    // Large odd multipliers (Teschner et al. 2003 style) spread neighbouring cells over buckets.
    const std::uint64_t h = static_cast<std::uint64_t>(ix) * 73856093ull ^ static_cast<std::uint64_t>(iy) * 19349663ull ^
                            static_cast<std::uint64_t>(iz) * 83492791ull;
    return h % (offset_.size() - 1);
}

void SpatialHashGrid::build(std::span<const Box> boxes, double cell) {
    boxes_ = boxes;
    const std::size_t n = boxes.size();
    for (std::size_t i = 0; i < n; ++i)
        if (!boxes[i].lo.allFinite() || !boxes[i].hi.allFinite())
            throw SolverError("contact search: segment " + std::to_string(i) +
                              " has a non-finite bounding box (non-finite node coordinates)");
    if (cell <= 0.0) {
        double ext = 0.0;
        for (const auto& b : boxes) ext += (b.hi - b.lo).maxCoeff();
        cell = n ? ext / static_cast<double>(n) : 1.0;
    }
    h_ = cell > 0 ? cell : 1.0;
    // A few boxes much larger than the mean would cover very many cells: coarsen until the table
    // holds at most ~64 entries per box.
    for (;;) {
        double total = 0.0;
        for (const auto& b : boxes) {
            const Vec3 e = (b.hi - b.lo) / h_;
            total += (std::floor(e.x()) + 2) * (std::floor(e.y()) + 2) * (std::floor(e.z()) + 2);
        }
        if (total <= 64.0 * static_cast<double>(n) + 1000.0) break;
        h_ *= 2.0;
    }
    origin_ = Vec3::Zero();
    if (n) {
        origin_ = boxes[0].lo;
        for (const auto& b : boxes) origin_ = origin_.cwiseMin(b.lo);
    }
    const std::size_t buckets = std::max<std::size_t>(2 * n, 1);
    offset_.assign(buckets + 1, 0);
    auto cells = [&](const Box& b, auto&& visit) {
        const Eigen::Vector3d lo = (b.lo - origin_) / h_, hi = (b.hi - origin_) / h_;
        const long x0 = static_cast<long>(std::floor(lo.x())), x1 = static_cast<long>(std::floor(hi.x()));
        const long y0 = static_cast<long>(std::floor(lo.y())), y1 = static_cast<long>(std::floor(hi.y()));
        const long z0 = static_cast<long>(std::floor(lo.z())), z1 = static_cast<long>(std::floor(hi.z()));
        for (long i = x0; i <= x1; ++i)
            for (long j = y0; j <= y1; ++j)
                for (long k = z0; k <= z1; ++k) visit(bucket(i, j, k));
    };
    // Two passes (count, fill): a compressed bucket -> boxes table.
    for (std::size_t s = 0; s < n; ++s) cells(boxes[s], [&](std::uint64_t bk) { ++offset_[bk + 1]; });
    for (std::size_t k = 0; k < buckets; ++k) offset_[k + 1] += offset_[k];
    items_.resize(offset_[buckets]);
    std::vector<int> fill(offset_.begin(), offset_.end() - 1);
    for (std::size_t s = 0; s < n; ++s) cells(boxes[s], [&](std::uint64_t bk) { items_[fill[bk]++] = static_cast<int>(s); });
}

void SpatialHashGrid::query(const Vec3& p, std::vector<int>& out) const {
    if (offset_.size() < 2) return;
    const Eigen::Vector3d q = (p - origin_) / h_;
    const std::uint64_t bk = bucket(static_cast<long>(std::floor(q.x())), static_cast<long>(std::floor(q.y())),
                                    static_cast<long>(std::floor(q.z())));
    const std::size_t first = out.size();
    for (int k = offset_[bk]; k < offset_[bk + 1]; ++k)
        if (boxes_[items_[k]].contains(p)) out.push_back(items_[k]);
    // A box spanning several cells hashing to the same bucket appears more than once.
    std::sort(out.begin() + first, out.end());
    out.erase(std::unique(out.begin() + first, out.end()), out.end());
}

void brute_force_query(std::span<const Box> boxes, const Vec3& p, std::vector<int>& out) {
    for (std::size_t s = 0; s < boxes.size(); ++s)
        if (boxes[s].contains(p)) out.push_back(static_cast<int>(s));
}

CandidateList::CandidateList(double margin, int max_interval) : margin_(margin), max_interval_(max_interval) {
    if (!(margin > 0.0)) throw InputError("contact search: the margin must be > 0");
    if (max_interval < 1) throw InputError("contact search: the rebuild interval must be >= 1 cycle");
}

}  // namespace fem::contact
