#pragma once
// The element geometries the library knows, with their node counts and node orderings. Node order
// is Gmsh's (corner nodes first, counter-clockwise; quad8: mid-edge nodes 01, 12, 23, 30;
// hexahedron: bottom face 0-3, top face 4-7 above them; tet10: corners 0-3 then mid-edge nodes on
// edges 01, 12, 20, 03, 23, 13, i.e. node 8 between corners 2 and 3 and node 9 between 1 and 3 --
// verified with gmsh::model::mesh::getElementProperties, see mesh/gmsh.hpp). VTK's quadratic tetra
// takes 01, 12, 02, 03, 13, 23: nodes 8 and 9 swapped, which the VTU writer converts.
#include <string_view>

namespace fem {

enum class ElementShape {
    Point1,  // point mass
    Beam2,   // 2-node line (bar, beam)
    Tri3,    // 3-node triangle (shell or plane)
    Quad4,   // 4-node quadrilateral (shell or plane)
    Quad8,   // 8-node serendipity quadrilateral (PLANE82, SHELL93)
    Tet4,    // 4-node tetrahedron
    Tet10,   // 10-node tetrahedron
    Hex8,    // 8-node hexahedron
    Hex20,   // 20-node serendipity hexahedron (CalculiX/Abaqus C3D20 order, which is VTK's too: the 8
             // corners as hex8, then mid-edge nodes of edges 01 12 23 30, 45 56 67 74, 04 15 26 37)
};

std::string_view to_string(ElementShape shape);
int node_count(ElementShape shape);
/// Spatial dimension of the element's parametric domain: 0 point, 1 line, 2 surface, 3 solid.
int dimension(ElementShape shape);
/// Parses "hex8", "tet10", ... (as written by to_string); throws InputError for an unknown name.
ElementShape element_shape_from_string(std::string_view name);

}  // namespace fem
