#pragma once
// Hexahedral mesh of a solid ellipsoid (x/a)^2 + (y/b)^2 + (z/c)^2 <= 1, or of its half z <= 0 (a
// half-symmetric model cut by the plane z = 0), for the football and the ellipsoid of thesis Ch 4
// (Tables 4-2, 4-5).
//
// Layout: an O-grid ("cube-sphere"). A logical cube [-1, 1]^3 carries an inner block of
// nx x ny x nz hexahedra at inner_scale of the ellipsoid, surrounded by `layers` layers of
// hexahedra on each of its six faces that run out to the surface: a point q of the cube's surface
// goes to q / |q| on the unit sphere, layer l at the fraction l / layers between inner_scale q and
// q / |q|. Every logical point p is finally scaled to (a p_x, b p_y, c p_z). No element has a
// ~180 degree corner (a single mapped block on a sphere would), so no element is much smaller
// than the others. Half model: the elements with z <= 0; nz must be even.
//
// Counts (half model): elements nx ny nz/2 + layers (nx ny + (nx + ny) nz); the thesis's half
// football of Table 4-2 has 512 elements and 677 nodes; nx = ny = 8, nz = 4, layers = 3 gives
// 512 elements and 678 nodes (the nearest O-grid found; tests/mesh).
//
// Node sets: "symmetry" (the nodes on z = 0, half model only), "centre" (the node at the centre,
// when nx, ny, nz are even), "surface" (nodes on the ellipsoid's surface).
#include <string>

#include "core/types.hpp"
#include "mesh/mesh.hpp"

namespace fem {

struct EllipsoidGrid {
    int nx = 8, ny = 8, nz = 4;   // inner-block elements along x, y, z (z over the whole ellipsoid)
    int layers = 3;               // element layers from the inner block to the surface
    // The inner block spans [-s a, s a] x [-s b, s b] x [-s c, s c]; its corners must stay well
    // inside (s sqrt(3) < 1): the first ring layer's corner elements are 1 - s sqrt(3) thick there.
    // 0.4 keeps the football's smallest element (Table 2-1 length 5.1 mm) above the fingers' step.
    double inner_scale = 0.4;
};

/// Hexahedral ellipsoid with semi-axes (a, b, c) along x, y, z, centred at the origin; `half`:
/// only z <= 0. Throws InputError for non-positive axes or counts (nz odd with half).
Mesh hex_ellipsoid(const Vec3& semi_axes, const EllipsoidGrid& grid, bool half, std::string part = "ellipsoid");

}  // namespace fem
