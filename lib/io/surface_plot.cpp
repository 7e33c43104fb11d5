#include "io/surface_plot.hpp"

#include <algorithm>
#include <iomanip>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace fem::io {

void write_shaded_triangles(const std::filesystem::path& path, std::span<const std::array<Vec3, 3>> triangles,
                            const Vec3& light, double scale) {
    if (!(light.norm() > 0.0)) throw InputError("write_shaded_triangles: the light direction must not be zero");
    const Vec3 l = light.normalized();
    AtomicFile file(path);
    auto& out = file.stream();
    out << "# x y z shade: one pm3d block (two scan lines) per triangle\n" << std::setprecision(7);
    for (const auto& t : triangles) {
        const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]);
        const double shade = n.norm() > 0.0 ? 0.25 + 0.75 * std::max(0.0, n.normalized().dot(l)) : 0.25;
        auto point = [&](const Vec3& p) { out << scale * p.x() << ' ' << scale * p.y() << ' ' << scale * p.z() << ' ' << shade << '\n'; };
        point(t[0]);
        point(t[1]);
        out << '\n';
        point(t[2]);
        point(t[2]);
        out << "\n\n";
    }
    file.commit();
}

}  // namespace fem::io
