#pragma once
// Test meshes: the box of tet10 elements of fem::box_tets (box_hex8 with every hexahedron split into
// six tetrahedra around its main diagonal).
#include <string>

#include "mesh/mesh.hpp"

namespace fem::test {

inline Mesh box_tet10(double lx, double ly, double lz, int nx, int ny, int nz, std::string part = "box") {
    return box_tets(lx, ly, lz, nx, ny, nz, ElementShape::Tet10, std::move(part));
}

}  // namespace fem::test
