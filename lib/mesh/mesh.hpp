#pragma once
// The finite element mesh shared by every solver of the library: nodes, element blocks (one shape
// and one part name per block), and named node sets (supports, load points, contact surfaces).
// A "part" in the thesis's sense (finger, drum, object, plate, bracket) is a block name; several
// blocks may share a part name.
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/types.hpp"
#include "mesh/element_shape.hpp"

namespace fem {

struct ElementBlock {
    std::string part;                // part name, e.g. "finger"
    ElementShape shape = ElementShape::Hex8;
    std::vector<int> connectivity;   // node_count(shape) node indices per element, 0-based
    /// The element numbers of the file the block was read from (Gmsh element tags, deck element
    /// numbers), one per element; empty for a generated block, whose elements are 1, 2, ... in
    /// block order. Messages name an element by id() so that a user finds it in their own file.
    std::vector<long> ids;

    int nodes_per_element() const { return node_count(shape); }
    long id(int e) const { return ids.empty() ? e + 1L : ids[static_cast<std::size_t>(e)]; }
    int size() const { return static_cast<int>(connectivity.size()) / nodes_per_element(); }
    std::span<const int> element(int e) const {
        return {connectivity.data() + static_cast<std::size_t>(e) * nodes_per_element(),
                static_cast<std::size_t>(nodes_per_element())};
    }
    void add(std::span<const int> nodes) { connectivity.insert(connectivity.end(), nodes.begin(), nodes.end()); }
};

struct Mesh {
    std::vector<Vec3> nodes;
    std::vector<ElementBlock> blocks;
    std::map<std::string, std::vector<int>> node_sets;

    int node_count() const { return static_cast<int>(nodes.size()); }
    int element_count() const;
    int add_node(const Vec3& x) {
        nodes.push_back(x);
        return static_cast<int>(nodes.size()) - 1;
    }
    /// The node set `name`; throws InputError naming the set and listing the known ones.
    const std::vector<int>& node_set(std::string_view name) const;
    /// Indices of the blocks whose part is `part`; throws InputError when there are none.
    std::vector<int> blocks_of_part(std::string_view part) const;
    /// The nodes of the elements of `part`, ascending, each once; throws as blocks_of_part.
    std::vector<int> nodes_of_part(std::string_view part) const;
    /// Coordinates of the nodes of element e of block b (copied, for element routines).
    std::vector<Vec3> element_coordinates(int block, int e) const;
    /// Appends another mesh (its nodes renumbered after ours; node sets merged, names kept).
    void append(const Mesh& other);
    /// Moves every node by `offset`.
    void translate(const Vec3& offset);
    /// Nodes whose coordinates satisfy pred (e.g. the clamped root face).
    template <class Pred>
    std::vector<int> select_nodes(Pred pred) const {
        std::vector<int> ids;
        for (int i = 0; i < node_count(); ++i)
            if (pred(nodes[i])) ids.push_back(i);
        return ids;
    }
};

/// Signed volume measure of a solid at its centre (det J up to a positive factor, from the corner
/// nodes `x` in the shape's order): <= 0 for an inverted element; 1 for shapes that are not solids.
double centre_jacobian(ElementShape shape, const std::vector<Vec3>& x);

/// Checks the mesh: node indices in range, no element repeating a node, solids with positive
/// volume (Jacobian at the centre), no NaN coordinates. Throws InputError naming the block,
/// element and node.
void validate(const Mesh& mesh);

// --- structured generators (real geometry comes from the Gmsh reader or the finger mesher) ---------

/// nx x ny x nz hexahedra filling [0,lx] x [0,ly] x [0,lz], part `part`. Node sets: "x0", "x1",
/// "y0", "y1", "z0", "z1" (the six faces).
Mesh box_hex8(double lx, double ly, double lz, int nx, int ny, int nz, std::string part = "box");

/// The box of box_hex8 with 20-node hexahedra (mid-edge nodes shared between neighbours, order of
/// ElementShape::Hex20). Node sets as box_hex8, mid-edge nodes on the faces included.
Mesh box_hex20(double lx, double ly, double lz, int nx, int ny, int nz, std::string part = "box");

/// The box of box_hex8 with every hexahedron split into six tetrahedra around its main diagonal
/// (a conforming split of the structured grid), `shape` Tet4 or Tet10 (mid-edge nodes shared between
/// neighbours, Gmsh order: corners, then edges 01, 12, 02, 03, 23, 13). Node sets as box_hex8 ("x0",
/// "x1", ..., mid-edge nodes on those faces included).
Mesh box_tets(double lx, double ly, double lz, int nx, int ny, int nz, ElementShape shape = ElementShape::Tet10,
              std::string part = "box");

/// nx x ny quadrilaterals (Quad4 or Quad8) filling [0,lx] x [0,ly] in the z = 0 plane. Node sets
/// "x0", "x1", "y0", "y1" (the four edges).
Mesh rectangle_quads(double lx, double ly, int nx, int ny, ElementShape shape = ElementShape::Quad4,
                     std::string part = "plate");

/// nu x nv Quad4 elements filling the parallelogram centred at `centre` spanned by u and v (full
/// edge vectors), numbered counter-clockwise about u x v (their normal), part `part`: a flat rigid
/// surface such as the ground or a conveyor pallet's top. Node (i, j) = centre + (i/nu - 1/2) u +
/// (j/nv - 1/2) v is node j (nu + 1) + i.
Mesh parallelogram_quad4(const Vec3& centre, const Vec3& u, const Vec3& v, int nu, int nv, std::string part);

/// n two-node line elements from a to b, part `part`. Node sets "start" and "end".
Mesh line_beam2(const Vec3& a, const Vec3& b, int n, std::string part = "beam");

}  // namespace fem
