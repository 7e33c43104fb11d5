#include "topopt/filter.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/memory.hpp"

namespace fem::topopt {

// Memory of W before it is built: each element has about (ball of radius r) / (domain box) * n
// neighbours, counted in the dimensions the centroids span (a plane domain is 2D, a folded shell
// 3D), at most n; each costs a triplet and a stored entry (about 32 bytes together).
double Filter::estimated_bytes(std::span<const Vec3> c, double r) {
    if (c.empty()) return 0;
    Vec3 lo = c.front(), hi = lo;
    for (const auto& p : c) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const double n = static_cast<double>(c.size());
    double fraction = 1;
    for (int d = 0; d < 3; ++d) {
        const double extent = hi(d) - lo(d);
        if (extent > 0) fraction *= std::min(1.0, 2 * r / extent);
    }
    return 32.0 * n * std::max(1.0, std::min(n, fraction * n));
}

Filter::Filter(std::span<const Vec3> c, std::span<const double> v, double r) : radius_(r) {
    if (!(r > 0)) throw InputError(fmt::format("filter radius must be > 0, got {}", r));
    if (c.size() != v.size()) throw InputError("filter: one volume per element centroid expected");
    const int n = static_cast<int>(c.size());
    volume_ = Eigen::Map<const Eigen::VectorXd>(v.data(), n);
    require_memory(estimated_bytes(c, r), fmt::format("a filter of radius {:g} m over {} elements", r, n));

    // Bucket the centroids in cubes of edge r: the neighbours of an element lie in the 27 cubes
    // around its own.
    auto cell = [r](double t) { return static_cast<long long>(std::floor(t / r)); };
    auto key = [](long long i, long long j, long long k) {
        return (i * 73856093LL) ^ (j * 19349663LL) ^ (k * 83492791LL);
    };
    std::unordered_multimap<long long, int> buckets;
    buckets.reserve(2 * n);
    for (int e = 0; e < n; ++e) buckets.emplace(key(cell(c[e].x()), cell(c[e].y()), cell(c[e].z())), e);

    std::vector<Eigen::Triplet<double>> t;
    t.reserve(static_cast<std::size_t>(n) * 16);
    std::vector<std::pair<int, double>> row;
    for (int i = 0; i < n; ++i) {
        row.clear();
        const long long ci = cell(c[i].x()), cj = cell(c[i].y()), ck = cell(c[i].z());
        for (long long a = ci - 1; a <= ci + 1; ++a)
            for (long long b = cj - 1; b <= cj + 1; ++b)
                for (long long d = ck - 1; d <= ck + 1; ++d) {
                    auto [lo, hi] = buckets.equal_range(key(a, b, d));
                    for (auto it = lo; it != hi; ++it) {
                        const int j = it->second;
                        // Hash collisions may bring far elements: the distance test discards them.
                        const double h = r - (c[i] - c[j]).norm();
                        if (h > 0) row.emplace_back(j, h * v[j]);
                    }
                }
        std::sort(row.begin(), row.end());
        row.erase(std::unique(row.begin(), row.end()), row.end());  // a cube key seen twice
        double sum = 0;
        for (auto& [j, w] : row) sum += w;
        for (auto& [j, w] : row) t.emplace_back(i, j, w / sum);
    }
    W_.resize(n, n);
    W_.setFromTriplets(t.begin(), t.end());
}

Eigen::VectorXd Filter::sensitivities(const Eigen::VectorXd& x, const Eigen::VectorXd& dc) const {
    const Eigen::VectorXd per_volume = x.cwiseProduct(dc).cwiseQuotient(volume_);
    Eigen::VectorXd out = W_ * per_volume;
    for (Eigen::Index i = 0; i < out.size(); ++i) out(i) *= volume_(i) / std::max(1e-3, x(i));
    return out;
}

}  // namespace fem::topopt
