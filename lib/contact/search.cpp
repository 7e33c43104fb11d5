#include "contact/search.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "io/hdf5.hpp"

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

namespace {
Eigen::MatrixXd rows_of(const std::vector<Vec3>& v) {
    Eigen::MatrixXd m(v.size(), 3);
    for (std::size_t i = 0; i < v.size(); ++i) m.row(i) = v[i].transpose();
    return m;
}
std::vector<Vec3> vec3s(const Eigen::MatrixXd& m) {
    std::vector<Vec3> v(m.rows());
    for (Eigen::Index i = 0; i < m.rows(); ++i) v[i] = m.row(i).transpose();
    return v;
}
std::vector<long long> as_ll(const std::vector<int>& v) { return {v.begin(), v.end()}; }
std::vector<int> as_int(const std::vector<long long>& v) { return {v.begin(), v.end()}; }
}  // namespace

void CandidateList::save_state(io::H5Writer& w, const std::string& prefix) const {
    w.write_ints(prefix + "counters", {since_, rebuilds_, cycles_});
    w.write(prefix + "slave0", rows_of(slave0_));
    w.write(prefix + "master0", rows_of(master0_));
    w.write_ints(prefix + "offset", as_ll(offset_));
    w.write_ints(prefix + "items", as_ll(items_));
    Eigen::MatrixXd b(boxes_.size(), 6);
    for (std::size_t i = 0; i < boxes_.size(); ++i) b.row(i) << boxes_[i].lo.transpose(), boxes_[i].hi.transpose();
    w.write(prefix + "boxes", b);
}

void CandidateList::restore_state(const io::H5Reader& r, const std::string& prefix) {
    const auto c = r.read_ints(prefix + "counters");
    if (c.size() != 3) throw InputError("restart file '" + r.path().string() + "': bad " + prefix + "counters");
    since_ = static_cast<int>(c[0]);
    rebuilds_ = c[1];
    cycles_ = c[2];
    slave0_ = vec3s(r.read_matrix(prefix + "slave0"));
    master0_ = vec3s(r.read_matrix(prefix + "master0"));
    offset_ = as_int(r.read_ints(prefix + "offset"));
    items_ = as_int(r.read_ints(prefix + "items"));
    const Eigen::MatrixXd b = r.read_matrix(prefix + "boxes");
    boxes_.resize(b.rows());
    for (Eigen::Index i = 0; i < b.rows(); ++i) boxes_[i] = {b.row(i).head<3>().transpose(), b.row(i).tail<3>().transpose()};
}

}  // namespace fem::contact
