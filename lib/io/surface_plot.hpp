#pragma once
// 3D pictures of surface meshes with gnuplot (no ParaView needed): triangles written for gnuplot's
// pm3d with a Lambert shade per triangle, drawn by
//   set pm3d depthorder corners2color c1
//   splot 'file' using 1:2:3:4 with pm3d
// Each triangle is one pm3d block of two scan lines (a, b / c, c); the fourth column is the shade
// 0.25 + 0.75 max(0, n . light) of its outward unit normal n, which a grey or skin-coloured palette
// turns into a lit surface. The surface itself comes from the caller (e.g. the outer faces of a
// solid part: contact::ContactSurface::from_part, whose triangles are oriented outward).
#include <array>
#include <filesystem>
#include <span>

#include "core/types.hpp"

namespace fem::io {

/// Writes the triangles (corner coordinates, counter-clockwise seen from outside), each corner
/// multiplied by `scale` (e.g. 1000 for mm), shaded by the light coming from direction `light`.
/// Atomic (AtomicFile).
void write_shaded_triangles(const std::filesystem::path& path, std::span<const std::array<Vec3, 3>> triangles,
                            const Vec3& light, double scale = 1.0);

}  // namespace fem::io
